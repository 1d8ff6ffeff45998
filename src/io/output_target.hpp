// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Where a run may write its result folder. breastsim replaces only a folder
// it wrote itself: one that carries its marker file (.breastsim-result) and
// holds nothing but the files that marker lists. Everything else is refused
// before any work, with a message naming the path and the reason:
// the file-system root, $HOME, the working directory or one of their
// ancestors, a folder holding an input file, a file, a non-empty folder
// without the marker. `--force` lets a run take over an empty unmarked folder.
#include <filesystem>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace breastsim
{
/// The name of the marker file in every result folder breastsim writes.
inline constexpr const char* result_marker = ".breastsim-result";

/// Folders never replaced, whatever they hold (a test passes fake ones).
struct ProtectedPaths
{
  std::filesystem::path root, home, cwd;
  /// This process's: "/", $HOME (if set) and the working directory.
  static ProtectedPaths of_this_process();
};

struct OutputRules
{
  std::vector<std::filesystem::path> inputs; ///< files the run reads
  bool force = false;                        ///< may take over an empty unmarked folder
  ProtectedPaths protect = ProtectedPaths::of_this_process();
};

/// Absolute, with `..`, `.`, symlinks and trailing separators resolved.
/// Throws InputError naming `what` for an empty path.
std::filesystem::path normalise_path(const std::string& given, const std::string& what = "--out");

/// Why `target` (normalised) must not be replaced, or nothing if it may be.
std::optional<std::string> refusal_reason(const std::filesystem::path& target,
                                          const OutputRules& rules);

/// The marker of a folder: {"format", "version", "command", "created", "host",
/// "pid", "state" (staging|complete), "files" (relative paths)}.
nlohmann::json read_marker(const std::filesystem::path& dir);
/// Write the marker of `dir` listing every file below it.
void write_marker(const std::filesystem::path& dir, const std::string& state);
/// The command line of this process (for the marker), set once by main().
void set_command_line(int argc, char** argv);

/// A result folder that this run has claimed: checked, locked against a
/// second run into the same folder, stale staging folders of dead runs
/// removed. Collective: every rank gets the same verdict.
class OutputTarget
{
public:
  /// Throws InputError (on every rank) when the target is refused or locked.
  static OutputTarget claim(const std::string& given, const OutputRules& rules, MPI_Comm comm);
  OutputTarget(OutputTarget&&) noexcept;
  OutputTarget& operator=(OutputTarget&&) = delete;
  OutputTarget(const OutputTarget&) = delete;
  ~OutputTarget(); ///< releases the lock
  const std::filesystem::path& path() const { return _path; }
  const OutputRules& rules() const { return _rules; }

private:
  OutputTarget(std::filesystem::path p, OutputRules r) : _path(std::move(p)), _rules(std::move(r)) {}
  std::filesystem::path _path;
  OutputRules _rules;
  int _lock_fd = -1;
  std::filesystem::path _lock_file;
};

/// Name of the staging folder of `target` for process `pid`: a sibling.
std::filesystem::path staging_path(const std::filesystem::path& target, long pid);
/// Remove `<name>.partial-<pid>` siblings of `target` whose process is dead
/// and which carry breastsim's marker. Returns how many were removed.
int remove_stale_staging(const std::filesystem::path& target);

/// A single result file (measurements, recording, checkpoint): refused if it
/// exists and was not written by breastsim (JSON with "written_by":
/// "breastsim"), or is a folder, or `given` names a protected folder.
std::filesystem::path claim_output_file(const std::string& given, const OutputRules& rules,
                                        const std::string& what);
} // namespace breastsim
