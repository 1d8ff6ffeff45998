// SPDX-License-Identifier: LGPL-3.0-or-later
#include "simulate.hpp"
#include "case_options.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "output.hpp"
#include "output_options.hpp"
#include "surface_export.hpp"
#include "timer.hpp"
#include "viewer.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim
{
namespace
{
/// One object per Newton iteration of a posture; "solve" numbers the Newton
/// solves of the posture (from the guess, then each load step, rejected
/// attempts included), "load" is the load factor it solved at.
nlohmann::json records_json(const LoadPathReport& path)
{
  nlohmann::json records = nlohmann::json::array();
  for (std::size_t k = 0; k < path.solves.size(); ++k)
  {
    const auto& solve = path.solves[k];
    for (std::size_t i = 0; i < solve.newton.records.size(); ++i)
    {
      const NewtonRecord& n = solve.newton.records[i];
      records.push_back({{"solve", k},
                         {"load", solve.value},
                         {"iteration", i + 1},
                         {"residual_norm_N", n.residual_norm},
                         {"model_energy_J", n.energy},
                         {"step", n.step},
                         {"linear_iterations", n.linear_iterations},
                         {"eta", n.eta},
                         {"wall_time_s", n.seconds}});
    }
  }
  return records;
}

/// The grid sequencing ladder of summary.json: unknowns, set-up time, levels.
nlohmann::json coarse_start_json(const CoarseStart& coarse, const SimulationResult& res)
{
  nlohmann::json j = {{"unknowns", res.coarse_dofs}, {"setup_s", res.coarse_setup_seconds},
                      {"levels", nlohmann::json::array()}};
  for (std::size_t k = 0; k < coarse.num_levels(); ++k)
  {
    const NestedLevel& l = coarse.ladder()[k];
    j["levels"].push_back({{"unknowns", res.coarse_level_dofs[k]},
                           {"mesh_size_m", l.mesh_size},
                           {"order", l.order},
                           {"refinements", l.refinements}});
  }
  return j;
}
} // namespace

nlohmann::json newton_records_json(const std::vector<PostureResult>& rs)
{
  nlohmann::json j = nlohmann::json::array();
  for (const auto& r : rs)
    j.push_back({{"posture", r.posture.name}, {"records", records_json(r.path)}});
  return j;
}

std::string newton_table(const PostureResult& r)
{
  std::string s = fmt::format("Newton iterations of posture '{}' (theta = {:g} deg):\n", r.posture.name,
                              r.posture.theta_deg);
  s += fmt::format("{:>5} {:>6} {:>4} {:>11} {:>17} {:>7} {:>6} {:>8} {:>8}\n", "solve", "load", "it",
                   "|r| [N]", "half energy[J]", "step", "ksp", "eta", "time[s]");
  for (std::size_t k = 0; k < r.path.solves.size(); ++k)
  {
    const auto& solve = r.path.solves[k];
    for (std::size_t i = 0; i < solve.newton.records.size(); ++i)
    {
      const NewtonRecord& n = solve.newton.records[i];
      s += fmt::format("{:>5} {:>6.4g} {:>4} {:>11.4e} {:>17.10e} {:>7.4g} {:>6} {:>8.2e} {:>8.3f}\n", k,
                       solve.value, i + 1, n.residual_norm, n.energy, n.step, n.linear_iterations,
                       n.eta, n.seconds);
    }
    s += fmt::format("{:>5} {}: |r| = {:.3e} (tolerance {:.3e}) after {} iterations{}\n", "",
                     solve.newton.converged ? "converged" : "failed", solve.newton.residual_norm,
                     solve.newton.tolerance, solve.newton.iterations,
                     solve.newton.message.empty() ? "" : " (" + solve.newton.message + ")");
  }
  return s;
}

nlohmann::json to_json(const PostureResult& r)
{
  auto j = to_json(r.observables);
  j["posture"] = r.posture.name;
  j["theta_deg"] = r.posture.theta_deg;
  j["load_steps"] = r.path.steps;
  j["failed_load_steps"] = r.path.failed_steps;
  j["newton_iterations"] = r.path.newton_iterations;
  j["linear_iterations"] = r.path.linear_iterations;
  j["wall_time_s"] = r.seconds;
  j["min_det_F"] = r.min_det_F;
  if (std::isfinite(r.mean_pressure))
    j["mean_pressure_Pa"] = r.mean_pressure; // mixed formulation: int p dV / V
  j["coarse_start"] = r.coarse.used;
  j["coarse_newton_iterations"] = r.coarse.newton_iterations;
  j["coarse_level_newton_iterations"] = r.coarse.level_newton_iterations;
  return j;
}

std::string observables_table(const std::vector<PostureResult>& rs)
{
  std::string s = fmt::format("{:<12} {:>7} {:>24} {:>9} {:>8} {:>8} {:>9} {:>9} {:>7} {:>7}\n",
                              "posture", "theta", "nipple x,y,z [mm]", "proj[mm]", "zmin[mm]",
                              "zmax[mm]", "perim[mm]", "vol[cm3]", "newton", "time[s]");
  for (const auto& r : rs)
  {
    const auto& o = r.observables;
    s += fmt::format("{:<12} {:>7.1f} {:>7.2f},{:>7.2f},{:>7.2f} {:>9.2f} {:>8.2f} {:>8.2f} {:>9.2f} "
                     "{:>9.2f} {:>7d} {:>7.2f}\n",
                     r.posture.name, r.posture.theta_deg, 1e3 * o.nipple[0], 1e3 * o.nipple[1],
                     1e3 * o.nipple[2], 1e3 * o.projection, 1e3 * o.z_min, 1e3 * o.z_max,
                     1e3 * o.base_perimeter, 1e6 * o.volume, r.path.newton_iterations, r.seconds);
  }
  return s;
}

std::string newton_tables(const std::vector<PostureResult>& rs, const std::string& heading)
{
  std::string s;
  for (const auto& r : rs)
    s += heading + newton_table(r);
  return s;
}

std::vector<PostureResult> solve_postures(Model& model, const ObservableProbe& probe,
                                          const Config& c, const std::filesystem::path& dir,
                                          CoarseStart* coarse, const Progress& progress)
{
  NewtonSolver newton(model, NewtonOptions::from(c));
  const OutputOptions output = OutputOptions::from(c);
  std::vector<PostureResult> out;
  const auto postures = requested_postures(c);
  for (const auto& p : postures)
  {
    progress.report(fmt::format("posture {} ({} of {})", p.name, out.size() + 1, postures.size()),
                    static_cast<double>(out.size()) / static_cast<double>(postures.size()));
    log::info("solving posture '{}' (theta = {:g} deg)", p.name, p.theta_deg);
    out.push_back(solve_posture(model, newton, probe, p, c, coarse));
    write_fields(model, dir / ("displacement_" + p.name), output.xdmf, output.vtk);
    write_surface(model, p.name, p.theta_deg, dir / ("surface_" + p.name + ".json"));
  }
  return out;
}

SimulationResult simulate(const Config& c, const OutputTarget& out, MPI_Comm comm, const Progress& progress)
{
  SimulationResult res;
  // Stages: meshing, the N postures (and the pictures): share 1 / (N + 1 (+ 1)) each.
  const bool pictures = OutputOptions::from(c).pictures_on();
  const double postures = static_cast<double>(requested_postures(c).size());
  const double stages = postures + 1 + (pictures ? 1 : 0);
  progress.report("meshing", 0);
  const CaseOptions case_options = CaseOptions::from(c);
  check_tissue_formulation(c); // e.g. a mixed case needs P2: refused before the mesh
  if (pictures)
    check_picture_tools(comm); // fail before the solves, not after
  auto mesh = [&]
  {
    Stopwatch meshing("simulate: mesh");
    auto m = build_neutral_mesh(c, comm);
    res.mesh_seconds = meshing.seconds();
    return m;
  }();
  res.quality = mesh_quality(*mesh.mesh);
  log::info("mesh: {} tetrahedra (P{}), min/max dihedral {:.1f}/{:.1f} deg, min radius ratio "
            "{:.3f}, {:.2f} s",
            res.quality.num_cells, mesh.degree, res.quality.min_dihedral_deg,
            res.quality.max_dihedral_deg, res.quality.min_radius_ratio, res.mesh_seconds);

  Model model(mesh, Constraints{true, case_options.fixed_base}, case_options.formulation);
  apply_parameters(c, model);
  res.dofs = model.num_dofs();
  res.linear_solver = model.mixed() ? "direct" : resolved_linear_solver(NewtonOptions::from(c), res.dofs);
  ObservableProbe probe(model, case_options.geometry.nipple());
  log::info("model: {} unknowns, linear solver {}, terms on: {}", res.dofs, res.linear_solver,
            [&] {
              std::string s;
              for (const auto& t : model.term_names())
                if (model.term_on(t))
                  s += (s.empty() ? "" : ", ") + t;
              return s;
            }());

  // Grid sequencing interpolates displacement levels: not for the mixed state.
  const auto coarse = model.mixed() ? nullptr : make_coarse_start(c, model);
  if (coarse)
  {
    res.coarse_dofs = coarse->coarse_dofs();
    res.coarse_level_dofs = coarse->level_dofs();
    res.coarse_setup_seconds = coarse->setup_seconds();
  }

  OutputDir dir(out, comm);
  res.postures = solve_postures(model, probe, c, dir.path(), coarse.get(),
                                progress.part(1 / stages, (1 + postures) / stages));

  nlohmann::json j;
  j["case"] = case_options.name;
  j["mesh"] = to_json(res.quality);
  j["mesh"]["order"] = mesh.degree;
  j["mesh"]["wall_time_s"] = res.mesh_seconds;
  j["unknowns"] = res.dofs;
  j["tissue_formulation"] = to_string(case_options.formulation);
  j["linear_solver"] = res.linear_solver;
  if (coarse)
    j["coarse_start"] = coarse_start_json(*coarse, res);
  int size;
  MPI_Comm_size(comm, &size);
  j["mpi_ranks"] = size;
  j["postures"] = nlohmann::json::array();
  for (const auto& r : res.postures)
    j["postures"].push_back(to_json(r));
  j["newton_records"] = newton_records_json(res.postures);
  write_json(dir.path() / "summary.json", j, comm);
  write_text(dir.path() / "case.resolved.toml", c.to_toml(), comm);
  if (pictures)
  {
    progress.report("pictures", (stages - 1) / stages);
    render_pictures(dir.path(), {}, comm);
  }
  dir.commit();
  progress.report("finished", 1);
  return res;
}
} // namespace breastsim
