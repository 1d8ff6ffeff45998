// SPDX-License-Identifier: LGPL-3.0-or-later
#include "calibrate_request.hpp"
#include "case_groups.hpp"
#include "geometry_options.hpp"
#include "errors.hpp"
#include "json_file.hpp"
#include <cstdio>
#include <fmt/format.h>

namespace breastsim::calibration
{
void check_calibrate_request(const CalibrateRequest& r, const Config& start)
{
  if (r.max_evals < 1)
    throw InputError(fmt::format("--max-evals = {} must be >= 1", r.max_evals));
  const double h = HalfCapSpec::from(start).mesh_size;
  if (r.correction_mesh_size != 0 && !(r.correction_mesh_size > 0 && r.correction_mesh_size < h))
    throw InputError(fmt::format("--correction-mesh-size = {} must be in (0, {}) m: "
                                 "finer than the fit's geometry.mesh_size",
                                 r.correction_mesh_size, h));
  if (r.correction_mesh_size > 0)
  {
    Config fine = start; // the schema's range for mesh sizes, named in the message
    fine.set("geometry.mesh_size", r.correction_mesh_size);
    fine.validate();
  }
  CaseGroups::check(MPI_COMM_WORLD, r.ranks_per_case, "--ranks-per-case");
  // Checked here, before a long fit (render.py checks it again).
  int w = 0, ht = 0;
  char rest = 0;
  if (std::sscanf(r.picture_size.c_str(), "%dx%d%c", &w, &ht, &rest) != 2 || w < 100 || w > 8000
      || ht < 100 || ht > 8000)
    throw InputError(fmt::format("--size '{}' must be WIDTHxHEIGHT with both in [100, "
                                 "8000] pixels, e.g. 800x600",
                                 r.picture_size));
}

CalibrationData read_calibration_data(const std::string& file)
{
  const auto doc = read_json_file(file, "measurements file");
  CalibrationData d;
  if (is_recording(doc))
    d.recording = parse_recording(doc, file);
  else
    d.measurements = parse_measurements(doc, file);
  return d;
}
} // namespace breastsim::calibration
