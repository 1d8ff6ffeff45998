// SPDX-License-Identifier: LGPL-3.0-or-later
#include "surgery.hpp"
#include "dense_table.hpp"
#include "case_options.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "output_options.hpp"
#include "coarse_start.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "output.hpp"
#include "reference_reset.hpp"
#include "timer.hpp"
#include "viewer.hpp"
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/utils.h>
#include <fmt/format.h>
#include <cmath>
#include <limits>
#include <numeric>

namespace breastsim
{
namespace
{
std::array<int, 5> suture_tags()
{
  return {generated::tag("base"), generated::tag("skin"), generated::tag("symmetry"),
          generated::tag("suture_abd"), generated::tag("suture_bcd")};
}
} // namespace

double max_suture_gap(const Model& m)
{
  const auto X = m.space()->tabulate_dof_coordinates(false);
  auto u = m.displacement()->x()->array();
  double gap = 0;
  // suture_abd -> plane x = 0 (component 0); suture_bcd -> plane y = 0 (component 1).
  for (auto [tag, comp] : {std::pair<const char*, int>{"suture_abd", 0}, {"suture_bcd", 1}})
    for (auto n : m.boundary_nodes(tag))
      gap = std::max(gap, std::abs(X[3 * n + comp] + u[3 * n + comp]));
  double global = 0;
  MPI_Allreduce(&gap, &global, 1, MPI_DOUBLE, MPI_MAX, m.mesh().mesh->comm());
  return global;
}

FoldSite fold_site(Model& model)
{
  const TaggedDolfinxMesh& tm = model.mesh();
  // det F at the check points, then at the centroid (forms/geometry_forms.py).
  auto expr = dolfinx::fem::create_expression<T>(*generated::detF_expression(tm.degree),
                                                  {{"u", model.displacement()}}, {}, tm.mesh);
  const std::int32_t nc = tm.mesh->topology().index_map(3)->size_local();
  std::vector<std::int32_t> cells(nc);
  std::iota(cells.begin(), cells.end(), 0);
  const std::size_t np = expr.X().second[0];
  DenseTable det{std::vector<double>(nc * np), np};
  expr.eval(std::span<const std::int32_t>(cells), det);
  int rank;
  MPI_Comm comm = tm.mesh->comm();
  MPI_Comm_rank(comm, &rank);
  struct { double value; int rank; } local{std::numeric_limits<double>::infinity(), rank}, global;
  std::int32_t worst = -1;
  for (std::int32_t c = 0; c < nc; ++c)
    for (std::size_t p = 0; p + 1 < np; ++p)
      if (det(c, p) < local.value || std::isnan(det(c, p)))
      {
        local.value = std::isnan(det(c, p)) ? -std::numeric_limits<double>::infinity() : det(c, p);
        worst = c;
      }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm);
  std::array<double, 5> buf{};
  if (rank == global.rank && worst >= 0)
  {
    // Centroid of the cell's corners (the first four geometry nodes).
    auto x = tm.mesh->geometry().x();
    auto nodes = tm.mesh->geometry().dofmap().links(worst);
    buf = {local.value, det(worst, np - 1), 0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
        buf[2 + i] += x[3 * nodes[k] + i] / 4;
  }
  MPI_Bcast(buf.data(), 5, MPI_DOUBLE, global.rank, comm);
  return {buf[0], buf[1], {buf[2], buf[3], buf[4]}};
}

namespace
{
/// Where the closure stopped: the fold site and the nearest incision point.
std::string describe_fold(Model& model, const Config& c)
{
  const FoldSite f = fold_site(model);
  std::string s = fmt::format("; in the last converged state the smallest det F at a check point is {:.3g}, in "
                              "the tetrahedron centred at ({:.1f}, {:.1f}, {:.1f}) mm (det F {:.3g} at its centroid)",
                              f.det_min, 1e3 * f.x[0], 1e3 * f.x[1], 1e3 * f.x[2], f.det_centroid);
  meshes::IncisionGeometry g;
  try
  {
    g = meshes::incision_geometry(HalfCapSpec::from(c), IncisionSpec::from(c));
  }
  catch (const InputError&)
  {
    return s; // a body without the case's incision (e.g. a test block)
  }
  const std::pair<const char*, meshes::Point> points[] = {{"A", g.A}, {"B", g.B}, {"C", g.C}, {"D", g.D}};
  double best = std::numeric_limits<double>::infinity();
  const char* name = "";
  for (const auto& [n, p] : points)
  {
    const double d = std::hypot(p[0] - f.x[0], p[1] - f.x[1], p[2] - f.x[2]);
    if (d < best)
      best = d, name = n;
  }
  return s + fmt::format(", {:.1f} mm from incision point {}", 1e3 * best, name);
}

/// Closure stepping, then the penalty raised x10 until the gap is at most
/// surgery.max_gap (the suture term on, gravity off).
void close_and_tighten(Model& model, const Config& c, SutureReport& rep)
{
  NewtonSolver newton(model, NewtonOptions::from(c));
  // Force scale: the suture pull at the start of closure.
  model.set_parameter("closure", {1.0});
  const double f_ref = model.residual_norm("sutures");
  LoadStepOptions opt = LoadStepOptions::from(c);
  opt.initial_step = std::min(opt.initial_step, 0.25);
  rep.closure = continuation(model, newton, "closure", 0.0, 1.0, opt, "suture closure", f_ref);
  double k = model.parameter("k_suture")[0];
  rep.max_gap = max_suture_gap(model);
  const double tol = SurgeryOptions::from(c).max_gap;
  while (rep.max_gap > tol)
  {
    if (++rep.penalty_raises > 6)
      throw SolveError(fmt::format("suture gap {:.3g} m still above surgery.max_gap = {:.3g} m after "
                                   "raising the penalty to {:.3g} Pa/m", rep.max_gap, tol, k));
    auto path = continuation(model, newton, "k_suture", k, 10 * k, opt, "suture penalty", f_ref);
    rep.closure.newton_iterations += path.newton_iterations;
    rep.closure.linear_iterations += path.linear_iterations;
    k *= 10;
    rep.max_gap = max_suture_gap(model);
    log::info("suture penalty raised to {:.3g} Pa/m: largest gap {:.4f} mm", k, 1e3 * rep.max_gap);
  }
  rep.k_final = k;
}
} // namespace

SutureReport close_sutures(Model& model, const Config& c)
{
  Stopwatch clock("surgery: sutures");
  SutureReport rep;
  const bool gravity_on = model.term_on("gravity");
  model.set_term("sutures", true);
  model.set_term("gravity", false); // knitting happens in the neutral (gravity-free) state
  try
  {
    close_and_tighten(model, c, rep);
  }
  catch (const SolveError& e)
  {
    throw SolveError(e.what() + describe_fold(model, c));
  }
  model.set_term("gravity", gravity_on); // as before the knitting
  rep.seconds = clock.seconds();
  return rep;
}

namespace
{
/// The three meshes of a surgery.
struct SurgeryMeshes
{
  TaggedDolfinxMesh pre;      ///< the neutral cap
  TaggedDolfinxMesh cut;      ///< the remaining body after the incision
  TaggedDolfinxMesh resected; ///< the resected tissue
};

/// Mesh the neutral cap, the remaining body and the resected part; their
/// quality, the meshing time and the exact cap volume into `r`.
SurgeryMeshes mesh_surgery(const Config& c, MPI_Comm comm, SurgeryResult& r)
{
  Stopwatch clock("surgery: meshing");
  const auto cap = HalfCapSpec::from(c);
  const auto inc = IncisionSpec::from(c);
  int rank;
  MPI_Comm_rank(comm, &rank);
  auto pre_mesh = build_neutral_mesh(c, comm);
  meshes::TaggedMesh cut;
  cut.order = cap.order;
  meshes::TaggedMesh resected = cut;
  if (rank == 0)
  {
    cut = meshes::mesh_incised_cap(cap, inc, suture_tags());
    resected = meshes::mesh_resected_part(cap, inc, suture_tags());
  }
  SurgeryMeshes m{std::move(pre_mesh), to_dolfinx(comm, cut, cap.order),
                  to_dolfinx(comm, resected, cap.order)};
  r.seconds_mesh = clock.seconds();
  r.quality_pre = mesh_quality(*m.pre.mesh);
  r.quality_incised = mesh_quality(*m.cut.mesh);
  r.quality_resected = mesh_quality(*m.resected.mesh);
  // Exact cap volume pi H^2 (3 Rs - H) / 3 (full breast), for the balance
  // kept + resected = cap in the report.
  const double Rs = meshes::sphere_radius(cap.R, cap.H);
  r.cap_volume = M_PI * cap.H * cap.H * (3 * Rs - cap.H) / 3;
  return m;
}

/// 2. Incision and suturing (no gravity) of the remaining body `post`,
/// 3. its final neutral state (the new reference); fields into `dir`.
void incise_and_suture(Model& post, const Config& c, const std::filesystem::path& dir,
                       SurgeryResult& r)
{
  const OutputOptions output = OutputOptions::from(c);
  r.volume_remaining = 2 * post.volume();
  r.resected_volume = r.volume_pre - r.volume_remaining;
  log::info("surgery: resected volume {:.1f} cm^3 (full breast); closing the sutures",
            1e6 * r.resected_volume);
  write_fields(post, dir / "incised_neutral", output.xdmf, false);
  r.suture = close_sutures(post, c);
  write_fields(post, dir / "sutured", output.xdmf, output.vtk);
  // The new nipple is the material point A (the transposed nipple).
  r.new_nipple_neutral = ObservableProbe(post, r.incision.A).measure(post).nipple;
  reset_reference(post);
  // The knitted faces now hold their sutured (new reference) positions
  // normal to their planes and still slide: gap = u . n.
  post.set_parameter("closure", {0.0});
  write_fields(post, dir / "final_neutral", output.xdmf, false);
}
} // namespace

SurgeryResult surgery(const Config& c, const OutputTarget& out, MPI_Comm comm, const Progress& progress)
{
  SurgeryResult r;
  // Stages: meshing, pre-op postures, sutures, post-op postures (and the pictures).
  const double postures = static_cast<double>(requested_postures(c).size()),
               stages = 2 * postures + 2 + (OutputOptions::from(c).pictures_on() ? 1 : 0);
  const CaseOptions case_options = CaseOptions::from(c);
  case_options.geometry.require_parametric_cap("surgery (the incision cuts the cap)");
  // The incision first: it rejects bad parameters before any meshing.
  r.incision = meshes::incision_geometry(case_options.geometry, IncisionSpec::from(c));
  if (OutputOptions::from(c).pictures_on())
    check_picture_tools(comm);
  progress.report("meshing", 0);
  SurgeryMeshes bodies = mesh_surgery(c, comm, r);
  OutputDir dir(out, comm);
  std::filesystem::create_directories(dir.path() / "preop");
  std::filesystem::create_directories(dir.path() / "postop");

  // 0. The resected tissue: its mesh (with the facet tags) and volume.
  {
    Model res(bodies.resected, Constraints{false, false});
    r.resected_volume_mesh = 2 * res.volume();
    if (OutputOptions::from(c).xdmf)
      write_mesh_xdmf(bodies.resected, dir.path() / "resected.xdmf");
  }

  // 1. Pre-operative breast: the case's neutral cap, with grid sequencing as
  // in `simulate` (the post-operative body has no coarse counterpart).
  {
    Stopwatch clock("surgery: pre-operative postures");
    Model pre(bodies.pre, Constraints{true, case_options.fixed_base});
    apply_parameters(c, pre);
    r.volume_pre = 2 * pre.volume();
    log::info("surgery: pre-operative postures");
    const auto coarse = make_coarse_start(c, pre);
    r.pre = solve_postures(pre, ObservableProbe(pre, {0.0, case_options.geometry.H, 0.0}), c,
                           dir.path() / "preop", coarse.get(),
                           progress.part(1 / stages, (1 + postures) / stages, "pre-operative "));
    r.seconds_pre = clock.seconds();
  }

  // 2., 3. Incision, sutures, final neutral state.
  Model post(bodies.cut, Constraints{true, case_options.fixed_base});
  apply_parameters(c, post);
  progress.report("sutures", (1 + postures) / stages);
  incise_and_suture(post, c, dir.path(), r);

  // 4. Post-operative postures, summary, pictures.
  finish_surgery(post, c, dir, r, [&] { return to_json(r); }, progress, postures, stages, comm);
  return r;
}

void finish_surgery(Model& post, const Config& c, OutputDir& dir, SurgeryResult& r,
                    const std::function<nlohmann::json()>& summary, const Progress& progress,
                    double postures, double stages, MPI_Comm comm)
{
  // Post-operative postures from the new reference (sutures stay knitted).
  {
    Stopwatch clock("surgery: post-operative postures");
    log::info("surgery: post-operative postures");
    r.post = solve_postures(post, ObservableProbe(post, r.new_nipple_neutral), c, dir.path() / "postop", nullptr,
                            progress.part((2 + postures) / stages, (2 + 2 * postures) / stages, "post-operative "));
    r.seconds_post = clock.seconds();
  }
  write_json(dir.path() / "summary.json", summary(), comm);
  write_text(dir.path() / "case.resolved.toml", c.to_toml(), comm);
  // Pictures: each stage's postures, post-op against pre-op, and the 3D page.
  if (OutputOptions::from(c).pictures_on())
  {
    progress.report("pictures", (stages - 1) / stages);
    render_surgery_pictures(dir.path(), {}, comm);
  }
  dir.commit();
  progress.report("finished", 1);
}

nlohmann::json to_json(const SurgeryResult& r)
{
  nlohmann::json j;
  const auto& g = r.incision;
  j["incision"] = {{"A_m", g.A}, {"B_m", g.B}, {"C_m", g.C}, {"D_m", g.D},
                   {"P1_normal", g.n1}, {"P1_offset_m", g.c1}, {"P2_normal", g.n2}, {"P2_offset_m", g.c2}};
  j["volume_pre_m3"] = r.volume_pre;
  j["volume_remaining_m3"] = r.volume_remaining;
  j["resected_volume_m3"] = r.resected_volume;
  j["resected_volume_mesh_m3"] = r.resected_volume_mesh;
  j["cap_volume_m3"] = r.cap_volume;
  j["mesh_pre"] = to_json(r.quality_pre);
  j["mesh_incised"] = to_json(r.quality_incised);
  j["mesh_resected"] = to_json(r.quality_resected);
  j["new_nipple_neutral_m"] = r.new_nipple_neutral;
  j["suture"] = {{"max_gap_m", r.suture.max_gap}, {"k_final_Pa_per_m", r.suture.k_final},
                 {"closure_steps", r.suture.closure.steps},
                 {"failed_steps", r.suture.closure.failed_steps},
                 {"newton_iterations", r.suture.closure.newton_iterations},
                 {"penalty_raises", r.suture.penalty_raises}, {"wall_time_s", r.suture.seconds}};
  j["wall_time_s"] = {{"meshing", r.seconds_mesh}, {"preop", r.seconds_pre},
                      {"suturing", r.suture.seconds}, {"postop", r.seconds_post}};
  j["preop"] = nlohmann::json::array();
  for (const auto& p : r.pre)
    j["preop"].push_back(to_json(p));
  j["postop"] = nlohmann::json::array();
  for (const auto& p : r.post)
    j["postop"].push_back(to_json(p));
  j["newton_records"] = {{"preop", newton_records_json(r.pre)}, {"postop", newton_records_json(r.post)}};
  return j;
}

std::string surgery_table(const SurgeryResult& r)
{
  std::string s = fmt::format("resected volume {:.1f} cm^3 (of {:.1f}; resected-tissue mesh {:.1f} cm^3), "
                              "largest suture gap {:.4f} mm, suture stiffness {:.3g} Pa/m\n",
                              1e6 * r.resected_volume, 1e6 * r.volume_pre, 1e6 * r.resected_volume_mesh,
                              1e3 * r.suture.max_gap, r.suture.k_final);
  s += fmt::format("{:<12} {:>22} {:>22} {:>9} {:>9} {:>9} {:>9}\n", "posture", "nipple pre y,z [mm]",
                   "nipple post y,z [mm]", "proj pre", "proj post", "zmin pre", "zmin post");
  for (std::size_t i = 0; i < r.pre.size() && i < r.post.size(); ++i)
  {
    const auto &a = r.pre[i].observables, &b = r.post[i].observables;
    s += fmt::format("{:<12} {:>10.2f},{:>10.2f} {:>10.2f},{:>10.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f}\n",
                     r.pre[i].posture.name, 1e3 * a.nipple[1], 1e3 * a.nipple[2], 1e3 * b.nipple[1],
                     1e3 * b.nipple[2], 1e3 * a.projection, 1e3 * b.projection, 1e3 * a.z_min,
                     1e3 * b.z_min);
  }
  return s;
}
} // namespace breastsim
