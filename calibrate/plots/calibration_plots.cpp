// SPDX-License-Identifier: LGPL-3.0-or-later
#include "calibration_plots.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "viewer.hpp"
#include <vector>

namespace breastsim::calibration
{
void render_calibration_pictures(const std::filesystem::path& dir, const std::string& size,
                                 MPI_Comm comm)
{
  const std::string script = (viewer_dir() / "calibration_plots.py").string();
  log::info("plotting the calibration ({} px)", size);
  const int code = run_on_root({viewer_python(), script, dir.string(), "--size", size}, comm);
  if (code == 3 || code < 0)
    check_picture_tools(comm); // python3 or matplotlib missing: throws with the installation hint
  if (code == 2)
    throw InputError("calibration plots failed (see the message above)");
  if (code != 0)
    throw std::runtime_error("calibration plots (" + script + ") failed with exit code "
                             + std::to_string(code));
  render_pictures(dir, {"", size}, comm);
}
} // namespace breastsim::calibration
