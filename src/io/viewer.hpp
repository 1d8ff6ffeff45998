// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Pictures (PNG, matplotlib) and the 3D page (index.html, three.js) of a
// result folder, made by the Python scripts in src/viewer/ run under
// Debian's python3. Rank 0 runs them; the functions are collective and throw
// on every rank if a script failed.
#include <filesystem>
#include <mpi.h>
#include <string>
#include <vector>

namespace breastsim
{
struct PictureOptions
{
  std::filesystem::path compare;  ///< optional second result folder (pre vs post)
  std::string size = "800x600";   ///< picture size WIDTHxHEIGHT in pixels
  std::filesystem::path out;      ///< folder the pictures go to (default: the result folder)
};

/// Folder of render.py, page.py and web/ (the source tree's src/viewer, or
/// $BREASTSIM_VIEWER_DIR).
std::filesystem::path viewer_dir();
/// Python interpreter used for the scripts (/usr/bin/python3, or $BREASTSIM_PYTHON).
std::string viewer_python();

/// Collective. Run `argv` (no shell; interrupt::run_child) on rank 0 and give
/// every rank its exit code (-1: it could not run).
int run_on_root(const std::vector<std::string>& argv, MPI_Comm comm);

/// Collective. Throws std::runtime_error naming the missing piece and how to
/// install it unless python3 with matplotlib and numpy is available.
void check_picture_tools(MPI_Comm comm);

/// Collective. Render view_<posture>.png, overview.png (and compare_<posture>.png)
/// of the surface_<posture>.json files in `result_dir` into `result_dir`.
void render_pictures(const std::filesystem::path& result_dir, const PictureOptions& o,
                     MPI_Comm comm);

/// True if `dir` is a surgery result: preop/ and postop/ folders of postures.
bool is_surgery_result(const std::filesystem::path& dir);
/// Collective. The pictures of a surgery result `dir`: each stage's postures,
/// post-op against pre-op, and the 3D page postop/index.html, written into
/// `o.out` (default `dir`) in the same layout (`o.compare` is not used).
void render_surgery_pictures(const std::filesystem::path& dir, const PictureOptions& o,
                             MPI_Comm comm);

/// Collective. Run the viewer script `name` (in viewer_dir()) with `args`
/// under viewer_python() on rank 0; throws naming `what` if it fails.
void run_viewer_script(const std::string& name, const std::vector<std::string>& args,
                       const std::string& what, MPI_Comm comm);

/// Collective. Write the self-contained 3D page of `result_dir` to `page`
/// (default `result_dir`/index.html).
void write_view_page(const std::filesystem::path& result_dir,
                     const std::filesystem::path& compare, MPI_Comm comm,
                     const std::filesystem::path& page = {});
} // namespace breastsim
