// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Shared CLI helpers: load a case with --set overrides; pass PETSc options
// (checked); the --out/--force options and the claim of the result folder.
#include "config.hpp"
#include "output_target.hpp"
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace breastsim::cli
{
/// Load CASE.toml (every default if `file` is empty) and apply "key=value" overrides (validated).
Config load_case(const std::string& file, const std::vector<std::string>& sets);
/// Insert the case's solver.petsc_options and the command line's into PETSc
/// and check them on a small probe solver: a bad type or value is an
/// InputError naming the option.
void insert_petsc_options(const Config& c, const std::string& extra);

/// `--out DIR` and `--force` of a subcommand that writes a result folder.
struct OutputOption
{
  std::string out;
  bool force = false;
  CLI::Option* option = nullptr; ///< to tell `--out ""` from no --out
};
void add_output_option(CLI::App* app, OutputOption& o, const std::string& help);
/// The folder asked for: `o.out`, or `default_out` without --out
/// (InputError for an explicit `--out ""`).
std::string output_name(const OutputOption& o, const std::string& default_out);
/// Claim `o.out` (or `default_out`) for this run, refusing it (InputError,
/// every rank) unless breastsim may replace it; `inputs` are the run's input files.
OutputTarget claim_output(const OutputOption& o, const std::string& default_out,
                          const std::vector<std::string>& inputs);
/// Claim a single output file (measurements, recording, checkpoint).
std::filesystem::path claim_file(const std::string& file, const std::vector<std::string>& inputs,
                                 const std::string& what);
/// "pictures and the 3D page: breastsim view DIR" when the case made none
/// (output.pictures = none), else "".
std::string pictures_hint(const Config& c, const std::filesystem::path& dir);
} // namespace breastsim::cli
