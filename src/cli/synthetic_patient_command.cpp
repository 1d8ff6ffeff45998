// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim synthetic-patient --volume 500 --ptosis 0.3 ... --posture
// standing --out DIR`: a synthetic patient's reference breast, forward
// solved and sampled to a scan with holes and noise (src/jobs/scan_synthetic.hpp).
#include "case_options.hpp"
#include "command.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "option_checks.hpp"
#include "overrides.hpp"
#include "scan_synthetic.hpp"
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace breastsim::cli
{
namespace
{
struct SyntheticOptions
{
  std::string case_file, posture = "standing", format = "stl";
  double volume_cm3 = 500;
  SyntheticPatientRequest request;
  std::vector<std::string> sets;
  OutputOption out;
};

scan::ScanFormat parse_format(const std::string& f, bool& points_only)
{
  points_only = f == "ply-points" || f == "obj-points";
  if (f == "stl")
    return scan::ScanFormat::stl_binary;
  if (f == "stl-ascii")
    return scan::ScanFormat::stl_ascii;
  if (f == "ply" || f == "ply-points")
    return scan::ScanFormat::ply_binary;
  if (f == "ply-ascii")
    return scan::ScanFormat::ply_ascii;
  return scan::ScanFormat::obj;
}
} // namespace

Command add_synthetic_patient_command(CLI::App& root)
{
  auto o = std::make_shared<SyntheticOptions>();
  auto* app = root.add_subcommand("synthetic-patient", "test data without real patients: a non-cap reference breast, "
                                                       "forward-solved to a posture, sampled to a scan with holes and "
                                                       "noise (docs/SCANS.md)");
  auto& r = o->request;
  app->add_option("--case", o->case_file, "case file for the material and solver (default: every default)");
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  app->add_option("--volume", o->volume_cm3, "reference volume [cm^3], in [200, 1500]")->capture_default_str();
  app->add_option("--ptosis", r.shape.ptosis, "droop of the anterior part, in [0, 0.8]")->capture_default_str();
  app->add_option("--lateral", r.shape.lateral, "nipple turned laterally, in [-0.4, 0.4]")->capture_default_str();
  app->add_option("--asymmetry", r.shape.asymmetry, "fuller lateral and lower quadrants, in [0, 0.4]")
      ->capture_default_str();
  app->add_option("--aspect", r.shape.aspect, "height over footprint semi-axis, in [0.4, 1.2]")->capture_default_str();
  app->add_option("--posture", o->posture, "posture of the scan")
      ->check(CLI::IsMember({"standing", "supine", "all_fours", "prone"}))->capture_default_str();
  app->add_option("--noise", r.noise, "noise standard deviation along the skin normal [m], in [0, 0.005]")
      ->capture_default_str();
  app->add_option("--holes", r.holes, "number of holes, in [0, 10]")->capture_default_str();
  app->add_option("--hole-radius", r.hole_radius, "hole radius [m], in [0.001, 0.02]")->capture_default_str();
  app->add_option("--format", o->format, "scan file format")
      ->check(CLI::IsMember({"stl", "stl-ascii", "ply", "ply-ascii", "ply-points", "obj", "obj-points"}))
      ->capture_default_str();
  app->add_option("--seed", r.seed, "random seed of holes and noise")->capture_default_str();
  app->add_option("--mesh-size", r.mesh_size, "reference mesh size [m], in [0.002, 0.02]")->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/synthetic-patient); replaced on success");
  return {app, [o]()
          {
            SyntheticPatientRequest req = o->request;
            req.shape.volume = 1e-6 * o->volume_cm3;
            check_range(req.noise, 0, 0.005, "--noise");
            check_range(req.holes, 0, 10, "--holes");
            check_range(req.hole_radius, 0.001, 0.02, "--hole-radius");
            check_range(req.mesh_size, 0.002, 0.02, "--mesh-size");
            req.format = parse_format(o->format, req.points_only);
            req.posture = named_posture(o->posture);
            const Config c = load_case(o->case_file, o->sets);
            std::vector<std::string> inputs;
            if (!o->case_file.empty())
              inputs.push_back(o->case_file);
            const auto out = claim_output(o->out, "results/synthetic-patient", inputs);
            const SyntheticPatientResult res = synthetic_patient(c, req, out, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << fmt::format("synthetic patient: reference volume {:.1f} cm3, nipple ({:.1f}, {:.1f}, "
                                       "{:.1f}) mm; {}: nipple ({:.1f}, {:.1f}, {:.1f}) mm; scan {} points, {} "
                                       "triangles\nresults written to {}/ ({}, reference.msh, case.reference.toml, "
                                       "truth.json)\n",
                                       1e6 * res.volume, 1e3 * res.nipple_reference[0], 1e3 * res.nipple_reference[1],
                                       1e3 * res.nipple_reference[2], req.posture.name, 1e3 * res.nipple_loaded[0],
                                       1e3 * res.nipple_loaded[1], 1e3 * res.nipple_loaded[2], res.scan_points,
                                       res.scan_triangles, out.path().string(), res.scan_file);
            return 0;
          }};
}
} // namespace breastsim::cli
