// SPDX-License-Identifier: LGPL-3.0-or-later
#include "calibration_output.hpp"
#include "calibration_plots.hpp"
#include "output.hpp"
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace breastsim::calibration
{
namespace
{
/// The calibrated case as `simulate` runs it from anywhere: its mesh file
/// (resolved against the starting case's folder) made absolute.
Config runnable_case(Config c)
{
  const std::string mesh_file = c.text("geometry.mesh_file");
  if (!mesh_file.empty())
    c.set("geometry.mesh_file", std::filesystem::absolute(mesh_file).lexically_normal().string());
  return c;
}
} // namespace

void write_calibration(const CalibrationResult& r, const OutputTarget& out, MPI_Comm comm,
                       const CalibrationOutputOptions& o)
{
  OutputDir dir(out, comm);
  write_text(dir.path() / "calibrated.toml", runnable_case(r.calibrated).to_toml(), comm);
  write_json(dir.path() / "report.json", r.report, comm);
  for (const auto& s : r.surfaces)
    write_json(dir.path() / ("surface_" + s["posture"].get<std::string>() + ".json"), s, comm);
  if (o.pictures)
    render_calibration_pictures(dir.path(), o.picture_size, comm);
  dir.commit();
}

std::string calibration_table(const nlohmann::json& rep)
{
  std::string s = fmt::format("{:<10} {:>12} {:>12} {:>9} {:>27}  {}\n", "parameter", "initial",
                              "fitted", "rel. SE", "95 % interval", "unit");
  for (const auto& p : rep["fit"])
  {
    const double se = p["relative_standard_error"].is_number()
                          ? p["relative_standard_error"].get<double>()
                          : std::nan("");
    s += fmt::format("{:<10} {:>12.5g} {:>12.5g} {:>8.2f}% [{:>12.5g}, {:>12.5g}]  {}{}\n",
                     p["name"].get<std::string>(), p["initial"].get<double>(),
                     p["fitted"].get<double>(), 100 * se,
                     p["interval_95"][0].is_number() ? p["interval_95"][0].get<double>() : 0.0,
                     p["interval_95"][1].is_number() ? p["interval_95"][1].get<double>()
                                                     : std::numeric_limits<double>::infinity(),
                     p["unit"].get<std::string>(),
                     p["flag"].get<std::string>().empty() ? "" : "  ! " + p["flag"].get<std::string>());
  }
  s += fmt::format("chi2 {:.4g} -> {:.4g} ({} measurements); {} evaluations, {} posture solves "
                   "({} warm-started), {:.1f} s\n",
                   rep["misfit"]["chi2_before"].get<double>(), rep["misfit"]["chi2_after"].get<double>(),
                   rep["misfit"]["measurements"].get<int>(), rep["evaluations"].get<int>(),
                   rep["posture_solves"].get<int>(), rep["warm_started_solves"].get<int>(),
                   rep["wall_time_s"].get<double>());
  return s;
}
} // namespace breastsim::calibration
