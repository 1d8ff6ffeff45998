// SPDX-License-Identifier: LGPL-3.0-or-later
#include "convergence.hpp"
#include "viewer.hpp"
#include "case_options.hpp"
#include "errors.hpp"
#include "interrupt.hpp"
#include "log.hpp"
#include "reference_reset.hpp"
#include "simulate.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "surgery.hpp"
#include "timer.hpp"
#include "breastsim_registry.hpp"
#include "mesh_from_gmsh.hpp"
#include "nested_mesh.hpp"
#include <cmath>
#include <cstdlib>
#include <dolfinx/common/IndexMap.h>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <spdlog/spdlog.h>

namespace breastsim
{
namespace
{
/// What one level of a study measures: the observables of the solved
/// posture and, for the surgery stage, the incision numbers.
struct LevelValues
{
  Observables o;
  double resected_volume = 0, max_gap = 0;
};

struct QuantityInfo
{
  std::string name, unit;
  double (*get)(const LevelValues&);
  bool surgery_only = false;
};

const std::vector<QuantityInfo>& quantity_table()
{
  static const std::vector<QuantityInfo> q = {
      {"nipple_x", "m", [](const LevelValues& v) { return v.o.nipple[0]; }},
      {"nipple_y", "m", [](const LevelValues& v) { return v.o.nipple[1]; }},
      {"nipple_z", "m", [](const LevelValues& v) { return v.o.nipple[2]; }},
      {"projection", "m", [](const LevelValues& v) { return v.o.projection; }},
      {"z_min", "m", [](const LevelValues& v) { return v.o.z_min; }},
      {"z_max", "m", [](const LevelValues& v) { return v.o.z_max; }},
      {"base_perimeter", "m", [](const LevelValues& v) { return v.o.base_perimeter; }},
      {"volume", "m^3", [](const LevelValues& v) { return v.o.volume; }},
      {"energy", "J", [](const LevelValues& v) { return v.o.energy; }},
      {"resected_volume", "m^3", [](const LevelValues& v) { return v.resected_volume; }, true},
      {"max_gap", "m", [](const LevelValues& v) { return v.max_gap; }, true},
  };
  return q;
}

const QuantityInfo& quantity(const std::string& name)
{
  for (const auto& q : quantity_table())
    if (q.name == name)
      return q;
  std::string known;
  for (const auto& q : quantity_table())
    known += (known.empty() ? "" : ", ") + q.name;
  throw InputError(fmt::format("--quantity: unknown quantity '{}' (known: {})", name, known));
}

nlohmann::json jval(double x)
{
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}
} // namespace

Richardson richardson(double q0, double q1, double q2, double r, double Fs)
{
  Richardson R;
  const double d1 = q1 - q0, d2 = q2 - q1;
  R.monotone = d1 * d2 > 0;
  R.order = std::log(std::abs(d1) / std::abs(d2)) / std::log(r);
  R.valid = std::isfinite(R.order) && R.order > 0;
  if (!R.valid)
  {
    R.extrapolated = std::numeric_limits<double>::quiet_NaN();
    R.gci = std::numeric_limits<double>::quiet_NaN();
    return R;
  }
  const double f = std::pow(r, R.order) - 1;
  R.extrapolated = q2 + d2 / f;
  R.gci = Fs * std::abs(d2 / q2) / f;
  return R;
}

namespace
{
/// The case's cap refined `refinements` times by red refinement, new skin
/// nodes snapped onto the cap (P2: straight midpoints, then snapped too).
TaggedDolfinxMesh red_refined_cap(const Config& c, MPI_Comm comm)
{
  auto spec = HalfCapSpec::from(c);
  const int order = spec.order, levels = spec.refinements;
  spec.order = 1;
  spec.refinements = 0;
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh m;
  m.order = order;
  if (rank == 0)
  {
    const int skin = generated::tag("skin");
    m = meshes::mesh_half_cap(spec, generated::tag("base"), skin, generated::tag("symmetry"));
    for (int l = 0; l < levels; ++l)
    {
      m = refine_red(m);
      snap_to_cap(m, spec.R, spec.H, skin);
    }
    if (order == 2)
    {
      m = straight_p2(m);
      snap_to_cap(m, spec.R, spec.H, skin);
    }
  }
  return to_dolfinx(comm, m, order);
}

/// Pre-operative stage: the standing posture of the case's cap at the level
/// (geometry.refinements of c).
LevelValues solve_preop_level(const Config& c, MPI_Comm comm, std::int64_t& cells,
                              std::int64_t& dofs, ConvergeRefinement refine)
{
  const CaseOptions case_options = CaseOptions::from(c);
  Model model(refine == ConvergeRefinement::red ? red_refined_cap(c, comm)
                                                : build_neutral_mesh(c, comm),
              Constraints{true, case_options.fixed_base}, case_options.formulation);
  apply_parameters(c, model);
  NewtonSolver newton(model, NewtonOptions::from(c));
  ObservableProbe probe(model, {0, case_options.geometry.H, 0});
  cells = model.mesh().mesh->topology().index_map(3)->size_global();
  dofs = model.num_dofs();
  LevelValues v;
  v.o = solve_posture(model, newton, probe, named_posture("standing"), c).observables;
  return v;
}

/// Surgery stage (the steps of surgery() without output): incised mesh at the
/// level, sutures closed without gravity, stresses reset, then the
/// post-operative standing posture from the new reference; the resected
/// volume from the pre- and post-operative meshes (full breast).
LevelValues solve_surgery_level(const Config& c, MPI_Comm comm, std::int64_t& cells,
                                std::int64_t& dofs)
{
  const auto cap = HalfCapSpec::from(c);
  const auto inc = IncisionSpec::from(c);
  const bool fixed_base = CaseOptions::from(c).fixed_base;
  const auto geo = meshes::incision_geometry(cap, inc);
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh cut;
  cut.order = cap.order;
  if (rank == 0)
    cut = meshes::mesh_incised_cap(cap, inc,
                                   {generated::tag("base"), generated::tag("skin"),
                                    generated::tag("symmetry"), generated::tag("suture_abd"),
                                    generated::tag("suture_bcd")});
  LevelValues v;
  {
    Model pre(build_neutral_mesh(c, comm), Constraints{true, fixed_base});
    v.resected_volume = 2 * pre.volume();
  }
  Model post(to_dolfinx(comm, cut, cap.order), Constraints{true, fixed_base});
  apply_parameters(c, post);
  v.resected_volume -= 2 * post.volume();
  v.max_gap = close_sutures(post, c).max_gap;
  const auto nipple = ObservableProbe(post, geo.A).measure(post).nipple;
  reset_reference(post);
  post.set_parameter("closure", {0.0});
  NewtonSolver newton(post, NewtonOptions::from(c));
  cells = post.mesh().mesh->topology().index_map(3)->size_global();
  dofs = post.num_dofs();
  v.o = solve_posture(post, newton, ObservableProbe(post, nipple), named_posture("standing"), c)
            .observables;
  return v;
}
} // namespace

std::vector<std::string> convergence_quantities()
{
  std::vector<std::string> n;
  for (const auto& q : quantity_table())
    n.push_back(q.name);
  return n;
}

std::vector<ConvergenceStudy> converge_case(const Config& c0, int levels,
                                            const std::vector<int>& orders,
                                            const std::vector<std::string>& quantities,
                                            MPI_Comm comm, ConvergeStage stage,
                                            ConvergeRefinement refine)
{
  if (levels < 3)
    throw InputError(fmt::format("--levels: at least 3 levels are needed (got {})", levels));
  if (levels > 5)
    throw InputError(fmt::format("--levels: at most 5 (geometry.refinements 0..4), got {}", levels));
  for (int p : orders)
    if (p != 1 && p != 2)
      throw InputError(fmt::format("--order: element order must be 1 or 2 (got {})", p));
  for (const auto& q : quantities)
    if (quantity(q).surgery_only && stage != ConvergeStage::surgery)
      throw InputError(fmt::format("--quantity: '{}' needs --stage surgery", q));
  if (stage == ConvergeStage::surgery && refine == ConvergeRefinement::red)
    throw InputError("--refine red: only with --stage preop (the surgery stage refines the "
                     "incised mesh with gmsh's splitting)");
  if (stage == ConvergeStage::surgery)
    meshes::incision_geometry(HalfCapSpec::from(c0), IncisionSpec::from(c0)); // rejects bad incisions first
  std::vector<ConvergenceStudy> out;
  for (int p : orders)
  {
    ConvergenceStudy s;
    s.element_order = p;
    s.refinement = refine == ConvergeRefinement::red ? "red" : "gmsh";
    s.posture = stage == ConvergeStage::surgery ? "standing (post-operative)" : "standing";
    for (const auto& q : quantities)
      s.quantities.push_back({q, quantity(q).unit, {}, {}, {}});
    for (int l = 0; l < levels; ++l)
    {
      Stopwatch clock("converge: one level");
      Config c = c0;
      c.set("geometry.order", std::int64_t(p));
      c.set("geometry.refinements", std::int64_t(l));
      c.validate();
      spdlog::info("converge: P{} refinement {} ({})", p, l, s.posture);
      std::int64_t cells = 0, dofs = 0;
      const LevelValues v = stage == ConvergeStage::surgery ? solve_surgery_level(c, comm, cells, dofs)
                                                            : solve_preop_level(c, comm, cells, dofs, refine);
      s.refinements.push_back(l);
      s.cells.push_back(cells);
      s.dofs.push_back(dofs);
      for (auto& q : s.quantities)
        q.values.push_back(quantity(q.name).get(v));
      s.seconds.push_back(clock.seconds());
    }
    for (auto& q : s.quantities)
    {
      for (std::size_t i = 0; i + 2 < q.values.size(); ++i)
        q.orders.push_back(richardson(q.values[i], q.values[i + 1], q.values[i + 2]).order);
      const std::size_t n = q.values.size();
      q.finest = richardson(q.values[n - 3], q.values[n - 2], q.values[n - 1]);
    }
    out.push_back(std::move(s));
  }
  return out;
}

nlohmann::json to_json(const ConvergenceStudy& s)
{
  nlohmann::json j;
  j["element_order"] = s.element_order;
  j["posture"] = s.posture;
  j["refinement"] = s.refinement;
  j["refinement_ratio"] = 2;
  j["safety_factor"] = 1.25;
  j["refinements"] = s.refinements;
  j["cells"] = s.cells;
  j["dofs"] = s.dofs;
  j["seconds"] = s.seconds;
  for (const auto& q : s.quantities)
  {
    nlohmann::json o;
    o["unit"] = q.unit;
    o["values"] = q.values;
    nlohmann::json ords = nlohmann::json::array();
    for (double x : q.orders)
      ords.push_back(jval(x));
    o["orders"] = ords;
    o["observed_order"] = jval(q.finest.order);
    o["richardson"] = jval(q.finest.extrapolated);
    o["gci_finest"] = jval(q.finest.gci);
    o["monotone"] = q.finest.monotone;
    o["valid"] = q.finest.valid;
    j["quantities"][q.name] = o;
  }
  return j;
}

std::string convergence_table(const ConvergenceStudy& s)
{
  std::string out = fmt::format("P{} posture {}, {} refinement: levels (cells)", s.element_order,
                                s.posture, s.refinement);
  for (std::size_t i = 0; i < s.cells.size(); ++i)
    out += fmt::format(" {} ({})", s.refinements[i], s.cells[i]);
  out += "\n";
  out += fmt::format("{:<15}", "quantity");
  for (std::size_t i = 0; i < s.cells.size(); ++i)
    out += fmt::format(" {:>14}", fmt::format("level {}", i));
  out += fmt::format(" {:>7} {:>14} {:>9}\n", "order", "Richardson", "GCI [%]");
  for (const auto& q : s.quantities)
  {
    out += fmt::format("{:<15}", q.name + " [" + q.unit + "]");
    for (double v : q.values)
      out += fmt::format(" {:>14.7g}", v);
    out += fmt::format(" {:>7.3f} {:>14.7g} {:>9.4f}{}\n", q.finest.order, q.finest.extrapolated,
                       100 * q.finest.gci, q.finest.monotone ? "" : "  (oscillatory)");
  }
  return out;
}

bool plot_convergence(const std::filesystem::path& json, const std::filesystem::path& png)
{
  const int rc = interrupt::run_child(
      {viewer_python(), (viewer_dir() / "convergence_plot.py").string(), json.string(), png.string()});
  return rc == 0 && std::filesystem::exists(png);
}
} // namespace breastsim
