#include "simulate.hpp"
#include "../meshes/half_cap.hpp"
#include "breastsim_registry.hpp"
#include "log.hpp"
#include "coarse_start.hpp"
#include "output.hpp"
#include "surface_export.hpp"
#include "viewer.hpp"
#include <chrono>
#include <fmt/format.h>

namespace breastsim
{
namespace
{
using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0)
{
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}

} // namespace

meshes::HalfCapSpec cap_spec(const Config& c)
{
  meshes::HalfCapSpec s;
  s.R = c.number("geometry.R");
  s.H = c.number("geometry.H");
  s.mesh_size = c.number("geometry.mesh_size");
  s.order = static_cast<int>(c.integer("geometry.order"));
  s.refinements = static_cast<int>(c.integer("geometry.refinements"));
  return s;
}

TaggedDolfinxMesh build_neutral_mesh(const Config& c, MPI_Comm comm)
{
  const meshes::HalfCapSpec spec = cap_spec(c);
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh m;
  m.order = spec.order;
  if (rank == 0)
    m = meshes::mesh_half_cap(spec, generated::tag("base"), generated::tag("skin"), generated::tag("symmetry"));
  return to_dolfinx(comm, m, spec.order);
}

void apply_parameters(const Config& c, Model& model)
{
  for (const auto& k : schema())
  {
    if (k.ufl_name.empty())
      continue;
    if (k.type == KeyType::number)
      model.set_parameter(k.ufl_name, {c.number(k.key)});
    else
      model.set_parameter(k.ufl_name, c.numbers(k.key));
  }
  for (const auto& t : model.term_names())
    model.set_term(t, c.flag("terms." + t));
}

NewtonOptions newton_options(const Config& c)
{
  NewtonOptions o;
  o.linear = c.text("solver.linear");
  o.amg_fine_smoother = c.text("solver.amg_fine_smoother");
  o.amg_cycle = c.text("solver.amg_cycle");
  o.direct_max_dofs = c.integer("solver.direct_max_dofs");
  o.rtol = c.number("solver.rtol");
  o.atol = c.number("solver.atol");
  o.max_iterations = static_cast<int>(c.integer("solver.max_iterations"));
  o.reuse_preconditioner = c.flag("solver.reuse_preconditioner");
  o.inexact = c.flag("solver.inexact_newton");
  o.forcing_max = c.number("solver.forcing_max");
  return o;
}

LoadStepOptions load_step_options(const Config& c)
{
  LoadStepOptions o;
  o.initial_step = c.number("solver.initial_load_step");
  o.min_step = c.number("solver.min_load_step");
  return o;
}

std::vector<Posture> requested_postures(const Config& c)
{
  std::vector<Posture> p;
  for (const auto& n : c.strings("postures.names"))
    p.push_back(named_posture(n));
  for (double t : c.numbers("postures.theta_deg"))
    p.push_back(posture_from_angle(t));
  return p;
}

double set_gravity(Model& model, const std::array<double, 3>& g)
{
  model.set_parameter("g_vec", {g[0], g[1], g[2]});
  model.set_parameter("load", {1.0});
  const double f_ext = model.residual_norm("gravity");
  model.set_parameter("load", {0.0});
  return f_ext;
}

PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, CoarseStart* coarse)
{
  const auto t0 = clock_type::now();
  PostureResult r;
  r.posture = posture;
  const std::string context = fmt::format("posture '{}' (theta = {:g} deg)", posture.name, posture.theta_deg);
  // Each posture starts from the neutral state (or from the coarse solution
  // of the same posture).
  model.displacement()->x()->set(0.0);
  const auto g = gravity_vector(posture.theta_deg, c.number("gravity.g"));
  const double f_ext = set_gravity(model, g);
  if (coarse)
  {
    model.set_parameter("load", {1.0});
    r.coarse = coarse->guess(model, g);
    if (r.coarse.used)
    {
      newton.invalidate_preconditioner();
      const NewtonReport nr = newton.solve(f_ext);
      r.path.newton_iterations = nr.iterations;
      r.path.linear_iterations = nr.linear_iterations;
      if (nr.converged)
        r.path.steps = 1;
      else
      {
        ++r.path.failed_steps;
        log::info("{}: Newton from the coarse solution failed ({}); solving from u = 0", context,
                  nr.message);
        model.displacement()->x()->set(0.0);
      }
    }
    else
      log::info("{}: coarse start not used: {}", context, r.coarse.reason);
    log::debug("{}: coarse start: {} Newton iterations on the levels below ({}), {} fine", context,
               r.coarse.newton_iterations, fmt::join(r.coarse.level_newton_iterations, ", "),
               r.path.newton_iterations);
  }
  if (r.path.steps == 0)
  {
    model.set_parameter("load", {0.0});
    const LoadPathReport p = continuation(model, newton, "load", 0.0, 1.0, load_step_options(c), context, f_ext);
    r.path.steps = p.steps;
    r.path.failed_steps += p.failed_steps;
    r.path.newton_iterations += p.newton_iterations;
    r.path.linear_iterations += p.linear_iterations;
  }
  r.observables = probe.measure(model);
  r.min_det_F = model.min_detF(); // > 0: no element of the deformed state is inverted
  r.seconds = since(t0);
  return r;
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

std::vector<PostureResult> solve_postures(Model& model, const ObservableProbe& probe,
                                          const Config& c, const std::filesystem::path& dir,
                                          CoarseStart* coarse)
{
  NewtonSolver newton(model, newton_options(c));
  std::vector<PostureResult> out;
  for (const auto& p : requested_postures(c))
  {
    log::info("solving posture '{}' (theta = {:g} deg)", p.name, p.theta_deg);
    out.push_back(solve_posture(model, newton, probe, p, c, coarse));
    write_fields(model, dir / ("displacement_" + p.name), c.flag("output.xdmf"), c.flag("output.vtk"));
    write_surface(model, p.name, p.theta_deg, dir / ("surface_" + p.name + ".json"));
  }
  return out;
}

SimulationResult simulate(const Config& c, const OutputTarget& out, MPI_Comm comm)
{
  SimulationResult res;
  check_picture_tools(comm); // fail before the solves, not after
  auto t0 = clock_type::now();
  auto mesh = build_neutral_mesh(c, comm);
  res.mesh_seconds = since(t0);
  res.quality = mesh_quality(*mesh.mesh);
  log::info("mesh: {} tetrahedra (P{}), min/max dihedral {:.1f}/{:.1f} deg, min radius ratio "
            "{:.3f}, {:.2f} s",
            res.quality.num_cells, mesh.degree, res.quality.min_dihedral_deg,
            res.quality.max_dihedral_deg, res.quality.min_radius_ratio, res.mesh_seconds);

  Model model(mesh, Constraints{true, c.flag("base.fixed")});
  apply_parameters(c, model);
  res.dofs = model.num_dofs();
  res.linear_solver = resolved_linear_solver(newton_options(c), res.dofs);
  ObservableProbe probe(model, {0.0, c.number("geometry.H"), 0.0});
  log::info("model: {} unknowns, linear solver {}, terms on: {}", res.dofs, res.linear_solver,
            [&] {
              std::string s;
              for (const auto& t : model.term_names())
                if (model.term_on(t))
                  s += (s.empty() ? "" : ", ") + t;
              return s;
            }());

  const auto coarse = make_coarse_start(c, model);
  if (coarse)
  {
    res.coarse_dofs = coarse->coarse_dofs();
    res.coarse_level_dofs = coarse->level_dofs();
    res.coarse_setup_seconds = coarse->setup_seconds();
  }

  OutputDir dir(out, comm);
  res.postures = solve_postures(model, probe, c, dir.path(), coarse.get());

  nlohmann::json j;
  j["case"] = c.text("case.name");
  j["mesh"] = to_json(res.quality);
  j["mesh"]["order"] = mesh.degree;
  j["mesh"]["wall_time_s"] = res.mesh_seconds;
  j["unknowns"] = res.dofs;
  j["linear_solver"] = res.linear_solver;
  if (coarse)
  {
    j["coarse_start"] = {{"unknowns", res.coarse_dofs}, {"setup_s", res.coarse_setup_seconds},
                         {"levels", nlohmann::json::array()}};
    for (std::size_t k = 0; k < coarse->num_levels(); ++k)
    {
      const NestedLevel& l = coarse->ladder()[k];
      j["coarse_start"]["levels"].push_back({{"unknowns", res.coarse_level_dofs[k]},
                                             {"mesh_size_m", l.mesh_size},
                                             {"order", l.order},
                                             {"refinements", l.refinements}});
    }
  }
  int size;
  MPI_Comm_size(comm, &size);
  j["mpi_ranks"] = size;
  j["postures"] = nlohmann::json::array();
  for (const auto& r : res.postures)
    j["postures"].push_back(to_json(r));
  write_json(dir.path() / "summary.json", j, comm);
  write_text(dir.path() / "case.resolved.toml", c.to_toml(), comm);
  render_pictures(dir.path(), {}, comm);
  dir.commit();
  return res;
}
} // namespace breastsim
