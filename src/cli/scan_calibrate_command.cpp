// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim scan-calibrate SCAN1 --posture standing SCAN2 --posture supine
// [SCAN3 --posture ...] --units mm --chest CHEST [--fit mu[,c]] [--predict
// SCAN --predict-posture all_fours] --out DIR`: the material and the neutral
// state fitted to scans of one breast in several postures
// (calibrate/fit/scan_calibration.hpp, docs/SCANS.md "Calibration with scans").
#include "breastsim_registry.hpp"
#include "case_options.hpp"
#include "command.hpp"
#include "errors.hpp"
#include "fit_parameters.hpp"
#include "log.hpp"
#include "on_root.hpp"
#include "option_checks.hpp"
#include "overrides.hpp"
#include "scan_calibration.hpp"
#include "scan_model_job.hpp"
#include "scan_readers.hpp"
#include "scan_series.hpp"
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

namespace breastsim::cli
{
namespace
{
struct ScanCalibrateOptions
{
  ScanCalibrateOptions() { model.mesh.mesh_size = 0; }
  std::vector<std::string> scans, postures, predict, predict_postures, sets;
  std::string chest, units, fit = "mu", case_file, up = "0,0,1", lateral = "1,0,0";
  double chest_margin = 0.005, min_sigma = 1e-4, mesh_ratio = 1.5;
  int max_iterations = 12;
  scan::ScanModelOptions model;
  OutputOption out;
};

/// Every option checked (InputError naming it) before any work.
void check_options(ScanCalibrateOptions& o, const Config& start, std::vector<calibration::FitParameter>& fit)
{
  if (o.scans.size() < 2)
    throw InputError(fmt::format("scans: {} given: at least two scans in different postures are needed (SCAN1 "
                                 "--posture A SCAN2 --posture B ...)", o.scans.size()));
  if (o.postures.size() != o.scans.size())
    throw InputError(fmt::format("--posture: {} given for {} scans: one --posture per scan, in the scans' order",
                                 o.postures.size(), o.scans.size()));
  if (o.predict_postures.size() != o.predict.size())
    throw InputError(fmt::format("--predict-posture: {} given for {} --predict scans: one per held-out scan",
                                 o.predict_postures.size(), o.predict.size()));
  std::set<std::string> seen;
  for (const auto& p : o.postures)
    if (!seen.insert(p).second)
      throw InputError(fmt::format("--posture = {} is given twice: the scans must be in different postures", p));
  for (const auto& p : o.predict_postures)
    if (seen.count(p))
      throw InputError(fmt::format("--predict-posture = {}: a fitted scan is in this posture; a held-out scan "
                                   "must be in another one", p));
  if (o.chest.empty())
    throw InputError("--chest is required: the chest wall, the same surface for every scan, registers the scans "
                     "in one chest-fixed frame");
  o.model.units = scan::parse_units(o.units, "--units");
  o.model.frame.up = parse_vector(o.up, "--up");
  o.model.frame.lateral = parse_vector(o.lateral, "--lateral");
  if (o.model.mesh.mesh_size != 0)
    check_range(o.model.mesh.mesh_size, 0.001, 0.02, "--mesh-size", "m (or 0: by the volume)");
  check_range(o.model.mesh.order, 1, 2, "--order", "");
  check_range(o.chest_margin, 0, 0.05, "--chest-margin", "m");
  check_range(o.model.limits.max_chest_rms, 1e-4, 0.05, "--max-chest-rms", "m");
  check_range(o.min_sigma, 1e-5, 0.01, "--min-sigma", "m");
  check_range(o.max_iterations, 1, 50, "--max-iterations", "");
  if (o.mesh_ratio != 0)
    check_range(o.mesh_ratio, 1.2, 3, "--mesh-error-ratio", "(or 0: no discretisation error estimate)");
  fit = calibration::parse_fit(o.fit, start);
  for (const auto& p : fit)
  {
    if (p.role == generated::FitRole::shape)
      throw InputError(fmt::format("--fit = {}: '{}' is a shape parameter of the cap; a scan's shape is its "
                                   "own (allowed here: the material, e.g. mu, c)", o.fit, p.name));
    if (p.key.rfind("base.", 0) == 0 && start.flag("base.fixed"))
      throw InputError(fmt::format("--fit = {}: '{}' ({}) is fitted but base.fixed = true clamps the base (no "
                                   "springs): set base.fixed = false or leave it out", o.fit, p.name, p.key));
  }
}

std::size_t nearest_node(const meshes::TaggedMesh& m, const scan::Vec3& p)
{
  std::size_t best = 0;
  double d_best = 1e300;
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
  {
    const double d = std::hypot(m.x[3 * n] - p[0], m.x[3 * n + 1] - p[1], m.x[3 * n + 2] - p[2]);
    if (d < d_best)
      d_best = d, best = n;
  }
  return best;
}

calibration::ScanPoints scan_points(const std::string& file, const std::string& posture,
                                    const std::vector<scan::Vec3>& pts, double noise, double min_sigma)
{
  calibration::ScanPoints s{file, named_posture(posture), {}, std::max(noise, min_sigma)};
  s.points.assign(pts.begin(), pts.end());
  return s;
}

/// Rank 0: the scans read, checked and meshed into `r` (mesh, points per
/// scan); `scans_json` describes them for the report; returns the numbers
/// every rank needs (mesh size, order, footprint radius, nipple y, z).
std::vector<double> read_scans_on_root(const ScanCalibrateOptions& o, calibration::ScanCalibrationRequest& r,
                                       nlohmann::json& scans_json)
{
  std::vector<double> numbers;
  on_root(MPI_COMM_WORLD, [&] { // every rank throws rank 0's InputError
    std::vector<std::filesystem::path> files(o.scans.begin(), o.scans.end());
    files.insert(files.end(), o.predict.begin(), o.predict.end());
    const scan::ScanSeries s = scan::build_scan_series(files, o.chest, o.model, generated::tag("base"),
                                                       generated::tag("skin"), generated::tag("symmetry"),
                                                       o.mesh_ratio);
    r.mesh = s.first.mesh.mesh;
    r.coarse_mesh = s.coarse.mesh;
    r.nipple_node = nearest_node(r.mesh, s.first.mesh.nipple);
    r.source = scan_points(o.scans[0], o.postures[0], s.first_points, s.first.noise_rms, o.min_sigma);
    nlohmann::json list = nlohmann::json::array();
    list.push_back({{"file", o.scans[0]}, {"posture", o.postures[0]}, {"role", "meshed"},
                    {"noise_rms_mm", 1e3 * s.first.noise_rms}});
    for (std::size_t k = 0; k < s.others.size(); ++k)
    {
      const bool held_out = k + 1 >= o.scans.size();
      const std::string& posture = held_out ? o.predict_postures[k + 1 - o.scans.size()] : o.postures[k + 1];
      (held_out ? r.predict : r.fit)
          .push_back(scan_points(s.others[k].file.string(), posture, s.others[k].points, s.others[k].noise_rms,
                                 o.min_sigma));
      list.push_back({{"file", s.others[k].file.string()}, {"posture", posture},
                      {"role", held_out ? "predicted" : "fitted"}, {"noise_rms_mm", 1e3 * s.others[k].noise_rms}});
    }
    const auto& f = s.first.frame;
    scans_json = {{"scans", list}, {"chest", o.chest},
                  {"frame", {{"origin_m", f.origin}, {"e_x", f.ex}, {"e_y", f.ey}, {"e_z", f.ez},
                             {"mirrored", f.mirrored()}}},
                  {"chest_wall", chest_json(s.first.chest)},
                  {"tetrahedra", r.mesh.num_cells()}, {"mesh_size_m", s.first.mesh_size},
                  {"chest_margin_m", o.chest_margin}};
    numbers = {s.first.mesh_size, double(r.mesh.order), f.footprint_radius, s.first.mesh.nipple[1],
               s.first.mesh.nipple[2]};
  });
  return numbers;
}

/// Rank 0's scan points on every rank (the residual vector's length).
void broadcast_points(calibration::ScanPoints& s)
{
  std::string t = rank_of(MPI_COMM_WORLD) == 0
                      ? nlohmann::json{{"f", s.file}, {"p", s.posture.name}, {"x", s.points}, {"s", s.sigma}}.dump()
                      : std::string();
  broadcast(t, MPI_COMM_WORLD);
  const auto j = nlohmann::json::parse(t);
  s = {j["f"].get<std::string>(), named_posture(j["p"].get<std::string>()),
       j["x"].get<std::vector<calibration::Point>>(), j["s"].get<double>()};
}

/// Collective: rank 0's numbers, report description and scan points on
/// every rank (the meshes are distributed by the model).
void broadcast_scans(calibration::ScanCalibrationRequest& r, std::vector<double>& numbers,
                     nlohmann::json& scans_json)
{
  std::string text
      = rank_of(MPI_COMM_WORLD) == 0 ? nlohmann::json{{"n", numbers}, {"j", scans_json}}.dump() : std::string();
  broadcast(text, MPI_COMM_WORLD);
  if (rank_of(MPI_COMM_WORLD) != 0)
  {
    const auto j = nlohmann::json::parse(text);
    numbers = j["n"].get<std::vector<double>>();
    scans_json = j["j"];
  }
  broadcast_points(r.source);
  std::size_t counts[2] = {r.fit.size(), r.predict.size()};
  MPI_Bcast(counts, 2, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  r.fit.resize(counts[0]);
  r.predict.resize(counts[1]);
  for (auto& s : r.fit)
    broadcast_points(s);
  for (auto& s : r.predict)
    broadcast_points(s);
}

/// Collective: the whole request: scans, start case, fit and solver settings.
calibration::ScanCalibrationRequest scan_request(const ScanCalibrateOptions& o, Config start,
                                                 const std::vector<calibration::FitParameter>& fit,
                                                 nlohmann::json& scans_json)
{
  calibration::ScanCalibrationRequest r;
  std::vector<double> numbers = read_scans_on_root(o, r, scans_json);
  broadcast_scans(r, numbers, scans_json);
  r.mesh.order = r.coarse_mesh.order = static_cast<int>(numbers[1]); // every rank: to_dolfinx's order
  start.set("geometry.mesh_size", numbers[0]);
  start.set("geometry.order", std::int64_t(numbers[1]));
  start.set("geometry.R", numbers[2]);
  // geometry.H and nipple_z (the nipple node) go with the mesh file into the calibrated case
  std::vector<std::string> postures = o.postures;
  postures.insert(postures.end(), o.predict_postures.begin(), o.predict_postures.end());
  start.set("postures.names", postures);
  start.set("postures.theta_deg", std::vector<double>{});
  r.start = start;
  r.parameters = fit;
  r.chest_margin = o.chest_margin;
  r.mesh_ratio = o.mesh_ratio;
  r.lsq.max_iterations = o.max_iterations;
  r.lsq.fd_step = 0.02; // 2 % of p: well above the inverse's 1e-6 m tolerance in the distances
  r.lsq.xtol = 2e-3;
  r.lsq.ftol_rel = 1e-5;
  return r;
}
} // namespace

Command add_scan_calibrate_command(CLI::App& root)
{
  auto o = std::make_shared<ScanCalibrateOptions>();
  auto* app = root.add_subcommand("scan-calibrate", "the material (mu; c) and the neutral state fitted to scans of "
                                                    "one breast in two or more postures, a held-out scan predicted "
                                                    "(docs/SCANS.md)");
  app->add_option("scans", o->scans, "the skin scans (STL, PLY, OBJ), each followed by its --posture; the first "
                                     "is meshed and inverted")->required();
  app->add_option("--posture", o->postures, "posture of each scan, in the scans' order")
      ->check(CLI::IsMember({"standing", "supine", "all_fours", "prone"}))->allow_extra_args(false);
  app->add_option("--units", o->units, "unit of the scans' coordinates: mm or m (required)")->required();
  app->add_option("--chest", o->chest, "the chest wall surface, the same for every scan (required: it registers "
                                       "the scans in one chest-fixed frame)");
  app->add_option("--fit", o->fit, "parameters fitted, comma separated (mu; c with the base springs on)")
      ->capture_default_str();
  app->add_option("--predict", o->predict, "a held-out scan predicted from the fit (repeatable)")
      ->allow_extra_args(false);
  app->add_option("--predict-posture", o->predict_postures, "posture of each --predict scan")
      ->check(CLI::IsMember({"standing", "supine", "all_fours", "prone"}))->allow_extra_args(false);
  app->add_option("--case", o->case_file, "case file: material and solver, the fitted keys' start values "
                                          "(default: every default)");
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  app->add_option("--up", o->up, "cranial direction in the scans' frame")->capture_default_str();
  app->add_option("--lateral", o->lateral, "direction toward the axilla in the scans' frame")->capture_default_str();
  app->add_option("--mesh-size", o->model.mesh.mesh_size, "element size [m], in [0.001, 0.02]; 0: by the volume "
                                                          "(as scan-model)")->capture_default_str();
  app->add_option("--order", o->model.mesh.order, "element order 1 or 2")->capture_default_str();
  app->add_option("--chest-margin", o->chest_margin, "scan points nearer the chest plane are not fitted [m], in "
                                                     "[0, 0.05]")->capture_default_str();
  app->add_option("--max-chest-rms", o->model.limits.max_chest_rms, "largest RMS distance of the chest wall "
                  "under the breast from the chest plane [m], in [1e-4, 0.05]")->capture_default_str();
  app->add_option("--min-sigma", o->min_sigma, "smallest noise sigma weighting a scan's points [m], in [1e-5, "
                                               "0.01] (each scan's own robust noise RMS above it)")
      ->capture_default_str();
  app->add_option("--max-iterations", o->max_iterations, "Levenberg-Marquardt iterations, in [1, 50]")
      ->capture_default_str();
  app->add_option("--mesh-error-ratio", o->mesh_ratio, "the fit is repeated on a mesh this many times coarser and "
                                                       "the difference widens the intervals (discretisation "
                                                       "error), in [1.2, 3]; 0: not estimated")
      ->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/scan-calibrate); replaced on success");
  return {app, [o]()
          {
            Config start = load_case(o->case_file, o->sets);
            std::vector<calibration::FitParameter> fit;
            check_options(*o, start, fit);
            std::vector<std::string> inputs = o->scans;
            inputs.insert(inputs.end(), o->predict.begin(), o->predict.end());
            inputs.push_back(o->chest);
            if (!o->case_file.empty())
              inputs.push_back(o->case_file);
            const auto out = claim_output(o->out, "results/scan-calibrate", inputs);

            nlohmann::json scans_json;
            const calibration::ScanCalibrationRequest r = scan_request(*o, start, fit, scans_json);
            const calibration::ScanCalibrationResult res = calibration::scan_calibrate(r, MPI_COMM_WORLD);
            calibration::write_scan_calibration(r, res, scans_json, out, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << calibration::scan_calibration_table(res) << "results written to "
                        << out.path().string() << "/ (report.json, case.toml, reference.msh, scan.msh)\n";
            return 0;
          }};
}
} // namespace breastsim::cli
