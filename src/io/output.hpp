// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Result folders: everything is written into a staging folder, a sibling of
// the claimed target (output_target.hpp), that only replaces the target when
// the whole run succeeded, so a failed or interrupted run leaves no partial
// output. The old result is moved aside first and removed only once the new
// one is in place.
#include "model.hpp"
#include "output_target.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim
{
class OutputDir
{
public:
  /// Collective. Creates `<target>.partial-<pid>` beside the target (rank 0).
  OutputDir(const OutputTarget& target, MPI_Comm comm);
  ~OutputDir(); ///< removes the staging folder unless committed
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  /// Staging path to write into.
  std::filesystem::path path() const { return _staging; }
  /// Collective. Write the marker and replace the target by the staging
  /// folder; throws InputError (nothing replaced) if the target changed
  /// meanwhile into something breastsim may not replace.
  void commit();
  /// Collective. Move the staged files one by one into the existing target
  /// folder (a finished result: `view` adds pictures), refusing before
  /// anything moves if an entry of the same name there is not a regular
  /// file; then list them in the target's marker. The staging folder is
  /// removed by the destructor.
  void commit_files();
  const std::filesystem::path& final_path() const { return _final; }

private:
  std::filesystem::path _final, _staging;
  OutputRules _rules;
  MPI_Comm _comm;
  bool _committed = false;
};

/// Write a JSON document (rank 0). Failures name the file and, when the
/// device is full, say so.
void write_json(const std::filesystem::path& file, const nlohmann::json& j, MPI_Comm comm);
/// Write a text file (rank 0).
void write_text(const std::filesystem::path& file, const std::string& text, MPI_Comm comm);
/// Write a single result file (rank 0) claimed by claim_output_file: through
/// a temporary sibling renamed into place; objects get "written_by".
void write_owned_json(const std::filesystem::path& file, nlohmann::json j, MPI_Comm comm);
/// Add the files below `dir` to its marker (after `view` wrote pictures).
void refresh_marker(const std::filesystem::path& dir, MPI_Comm comm);
/// Write the displacement of `model` on its mesh (XDMF; and VTK if `vtk`).
void write_fields(Model& model, const std::filesystem::path& stem, bool xdmf, bool vtk);
/// Collective. Write the mesh of `m` and its facet tags (base, skin, ...)
/// as XDMF to `file` (ParaView), with its HDF5 file beside it.
void write_mesh_xdmf(const TaggedDolfinxMesh& m, const std::filesystem::path& file);
} // namespace breastsim
