#pragma once
// Result folders: everything is written into a staging folder that only
// replaces the requested folder when the whole run succeeded, so a failed
// run leaves no partial output.
#include "model.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim
{
class OutputDir
{
public:
  /// Collective. Creates `<final>.partial-<pid>` (rank 0).
  OutputDir(std::filesystem::path final_dir, MPI_Comm comm);
  ~OutputDir(); ///< removes the staging folder unless committed
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  /// Staging path to write into.
  std::filesystem::path path() const { return _staging; }
  /// Collective. Replace the final folder by the staging folder.
  void commit();
  const std::filesystem::path& final_path() const { return _final; }

private:
  std::filesystem::path _final, _staging;
  MPI_Comm _comm;
  bool _committed = false;
};

/// Write a JSON document (rank 0).
void write_json(const std::filesystem::path& file, const nlohmann::json& j, MPI_Comm comm);
/// Write a text file (rank 0).
void write_text(const std::filesystem::path& file, const std::string& text, MPI_Comm comm);
/// Write the displacement of `model` on its mesh (XDMF; and VTK if `vtk`).
void write_fields(Model& model, const std::filesystem::path& stem, bool xdmf, bool vtk);
} // namespace breastsim
