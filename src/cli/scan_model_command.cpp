// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim scan-model SCAN --units mm --posture standing [--chest CHEST]
// [--nipple x,y,z] --out DIR`: a skin scan becomes a tagged mesh and a case
// (src/jobs/scan_model.hpp).
#include "command.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "option_checks.hpp"
#include "overrides.hpp"
#include "scan_model_job.hpp"
#include "scan_readers.hpp"
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <sstream>

namespace breastsim::cli
{
namespace
{
struct ScanOptions
{
  ScanOptions() { model.mesh.mesh_size = 0; } // by the breast's volume
  std::string skin, chest, units, posture = "standing", nipple, up = "0,0,1", lateral = "1,0,0", name = "scan";
  double theta = std::numeric_limits<double>::quiet_NaN();
  scan::ScanModelOptions model;
  OutputOption out;
};

/// The checked request (InputError on a bad option).
ScanModelRequest request(const ScanOptions& o)
{
  ScanModelRequest r;
  r.skin = o.skin;
  if (!o.chest.empty())
    r.chest = o.chest;
  r.options = o.model;
  r.options.units = scan::parse_units(o.units, "--units");
  const double k = r.options.units == scan::Units::mm ? 1e-3 : 1.0;
  if (!o.nipple.empty())
    r.options.frame.nipple = scan::operator*(k, parse_vector(o.nipple, "--nipple"));
  r.options.frame.up = parse_vector(o.up, "--up");
  r.options.frame.lateral = parse_vector(o.lateral, "--lateral");
  if (r.options.mesh.mesh_size != 0)
    check_range(r.options.mesh.mesh_size, 0.001, 0.02, "--mesh-size", "m");
  check_range(r.options.limits.max_hole, 0.001, 0.1, "--max-hole", "m");
  check_range(r.options.limits.max_noise, 1e-5, 0.01, "--max-noise", "m");
  check_range(r.options.limits.max_spike, 1e-4, 0.05, "--max-spike", "m");
  check_range(r.options.limits.max_chest_rms, 1e-4, 0.05, "--max-chest-rms", "m");
  check_range(r.options.mesh.order, 1, 2, "--order", "");
  check_range(r.options.degree, 2, 20, "--degree", "");
  if (!std::isnan(o.theta))
    check_range(o.theta, -180, 180, "--theta", "deg");
  r.posture = std::isnan(o.theta) ? named_posture(o.posture) : posture_from_angle(o.theta);
  r.name = o.name;
  return r;
}
} // namespace

Command add_scan_model_command(CLI::App& root)
{
  auto o = std::make_shared<ScanOptions>();
  auto* app = root.add_subcommand("scan-model", "a skin scan (STL, PLY, OBJ; a point cloud with --chest) recorded in a "
                                                "posture -> a tagged mesh and a case in the breast frame (docs/SCANS.md)");
  app->add_option("scan", o->skin, "the skin scan: .stl (ASCII or binary), .ply (ASCII or binary_little_endian), .obj")
      ->required();
  app->add_option("--units", o->units, "unit of the scan's coordinates: mm or m (required)")->required();
  app->add_option("--posture", o->posture, "posture the scan was recorded in")
      ->check(CLI::IsMember({"standing", "supine", "all_fours", "prone"}))->capture_default_str();
  app->add_option("--theta", o->theta, "chest angle theta [deg] instead of --posture, in [-180, 180]");
  app->add_option("--chest", o->chest, "the chest wall as a second surface (same unit); default: the plane through "
                                       "the scan's open boundary (its footprint)");
  app->add_option("--nipple", o->nipple, "nipple landmark x,y,z in the scan's frame and unit; default: the most "
                                         "anterior part of the skin");
  app->add_option("--up", o->up, "cranial direction in the scan's frame")->capture_default_str();
  app->add_option("--lateral", o->lateral, "direction toward the axilla of this breast in the scan's frame")
      ->capture_default_str();
  app->add_option("--mesh-size", o->model.mesh.mesh_size, "element size [m], in [0.001, 0.02]; 0: 6 mm (V / 500 "
                                                          "cm^3)^(1/3) within [4, 12] mm")->capture_default_str();
  app->add_option("--order", o->model.mesh.order, "element order 1 or 2")->capture_default_str();
  app->add_flag("--half", o->model.mesh.half, "mesh the half x >= 0 with a symmetry face (a symmetric breast)");
  app->add_option("--degree", o->model.degree, "degree of the smooth skin fit, in [2, 20]")->capture_default_str();
  app->add_option("--max-hole", o->model.limits.max_hole, "widest hole bridged [m], in [0.001, 0.1]")
      ->capture_default_str();
  app->add_option("--max-noise", o->model.limits.max_noise, "largest noise RMS accepted [m], in [1e-5, 0.01]")
      ->capture_default_str();
  app->add_option("--max-spike", o->model.limits.max_spike, "a point farther off the skin is a spike [m], in "
                                                            "[1e-4, 0.05]")->capture_default_str();
  app->add_option("--max-chest-rms", o->model.limits.max_chest_rms,
                  "largest RMS distance of the chest wall under the breast from the chest plane [m], in "
                  "[1e-4, 0.05]")->capture_default_str();
  app->add_option("--name", o->name, "case.name of the written case")->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/scan-model); replaced on success");
  return {app, [o]()
          {
            const ScanModelRequest r = request(*o);
            std::vector<std::string> inputs = {o->skin};
            if (!o->chest.empty())
              inputs.push_back(o->chest);
            const auto out = claim_output(o->out, "results/scan-model", inputs);
            const ScanModelResult res = scan_model(r, out, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << scan_model_table(res) << "results written to " << out.path().string()
                        << "/ (scan.msh, scan.xdmf, case.toml, frame.json, summary.json)\n";
            return 0;
          }};
}
} // namespace breastsim::cli
