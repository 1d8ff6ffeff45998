// SPDX-License-Identifier: LGPL-3.0-or-later
#include "viewer.hpp"
#include "assets.hpp"
#include "errors.hpp"
#include "interrupt.hpp"
#include "log.hpp"
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace breastsim
{
int run_on_root(const std::vector<std::string>& argv, MPI_Comm comm)
{
  int rank, code = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    code = interrupt::run_child(argv);
  MPI_Bcast(&code, 1, MPI_INT, 0, comm);
  return code;
}

namespace
{

std::string script(const char* name) { return (viewer_dir() / name).string(); }

void check_code(int code, const std::string& what)
{
  if (code == 2)
    throw InputError(what + " failed (see the message above)");
  if (code != 0)
    throw std::runtime_error(what + " failed with exit code " + std::to_string(code) +
                             " (see the message above)");
}
} // namespace

std::filesystem::path viewer_dir() { return asset_dir("viewer", "BREASTSIM_VIEWER_DIR"); }

std::string viewer_python()
{
  const char* p = std::getenv("BREASTSIM_PYTHON");
  return p ? p : "/usr/bin/python3";
}

void check_picture_tools(MPI_Comm comm)
{
  const std::string py = viewer_python();
  const int code = run_on_root({py, "-c", "import matplotlib, numpy"}, comm);
  if (code != 0)
    throw std::runtime_error(
        "pictures need " + py + " with matplotlib and numpy (" +
        (code < 0 ? py + " not found" : std::string("import failed")) +
        "): apt-get install python3-matplotlib python3-numpy (or run bash .ci/setup)");
  if (!std::filesystem::is_regular_file(script("render.py")))
    throw std::runtime_error("picture script " + script("render.py") +
                             " not found (set BREASTSIM_VIEWER_DIR to breastsim's src/viewer)");
}

void render_pictures(const std::filesystem::path& result_dir, const PictureOptions& o,
                     MPI_Comm comm)
{
  std::vector<std::string> argv = {viewer_python(), script("render.py"), result_dir.string(),
                                   "--size", o.size};
  if (!o.compare.empty())
    argv.insert(argv.end(), {"--compare", o.compare.string()});
  if (!o.out.empty())
    argv.insert(argv.end(), {"--out", o.out.string()});
  log::info("rendering pictures ({} px)", o.size);
  const int code = run_on_root(argv, comm);
  if (code == 3 || code < 0)
    check_picture_tools(comm); // python3 or matplotlib missing: throws with the installation hint
  check_code(code, "rendering the pictures of " + result_dir.string());
}

bool is_surgery_result(const std::filesystem::path& dir)
{
  namespace fs = std::filesystem;
  auto real_dir = [](const fs::path& p) { return fs::is_directory(fs::symlink_status(p)); };
  return real_dir(dir / "preop") && real_dir(dir / "postop");
}

void render_surgery_pictures(const std::filesystem::path& dir, const PictureOptions& o,
                             MPI_Comm comm)
{
  const std::filesystem::path to = o.out.empty() ? dir : o.out;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0 && to != dir)
    for (const char* stage : {"preop", "postop"})
      std::filesystem::create_directory(to / stage);
  render_pictures(dir / "preop", {"", o.size, to / "preop"}, comm);
  render_pictures(dir / "postop", {dir / "preop", o.size, to / "postop"}, comm);
  write_view_page(dir / "postop", dir / "preop", comm, to / "postop" / "index.html");
}

void run_viewer_script(const std::string& name, const std::vector<std::string>& args,
                       const std::string& what, MPI_Comm comm)
{
  std::vector<std::string> argv = {viewer_python(), (viewer_dir() / name).string()};
  argv.insert(argv.end(), args.begin(), args.end());
  check_code(run_on_root(argv, comm), what);
}

void write_view_page(const std::filesystem::path& result_dir,
                     const std::filesystem::path& compare, MPI_Comm comm,
                     const std::filesystem::path& page)
{
  std::vector<std::string> argv = {viewer_python(), script("page.py"), result_dir.string()};
  if (!compare.empty())
    argv.insert(argv.end(), {"--compare", compare.string()});
  if (!page.empty())
    argv.insert(argv.end(), {"--out", page.string()});
  check_code(run_on_root(argv, comm), "writing the 3D page of " + result_dir.string());
}
} // namespace breastsim
