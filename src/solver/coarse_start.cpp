// SPDX-License-Identifier: LGPL-3.0-or-later
#include "coarse_start.hpp"
#include "errors.hpp"
#include "geometry_options.hpp"
#include "log.hpp"
#include "point_location.hpp"
#include "model_setup.hpp"
#include "timer.hpp"
#include "warm_start.hpp"
#include <algorithm>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/fem/DofMap.h>
#include <cmath>
#include <fmt/format.h>
#include <mpi.h>

namespace breastsim
{
namespace
{
/// The case on one mesh of the ladder: same geometry and physics.
Config level_config(const Config& c, const NestedLevel& l)
{
  Config lc = c;
  lc.set("geometry.mesh_size", l.mesh_size);
  lc.set("geometry.order", std::int64_t{l.order});
  lc.set("geometry.refinements", std::int64_t{l.refinements});
  lc.set("solver.linear", std::string("auto"));
  // The levels only provide the fine start: the difference between two
  // levels' solutions is far above this tolerance.
  lc.set("solver.rtol", CoarseStartOptions::from(c).rtol);
  return lc;
}

std::string describe(const NestedLevel& l)
{
  return l.refinements > 0 ? fmt::format("{:g} m x{} refined, P{}", l.mesh_size, l.refinements, l.order)
                           : fmt::format("{:g} m, P{}", l.mesh_size, l.order);
}
} // namespace

double relative_unknowns(double mesh_size, int order, int refinements)
{
  return std::pow(1.0 / mesh_size, 3) * (order == 2 ? 7.0 : 1.0)
         * std::pow(8.0, static_cast<double>(refinements));
}

std::vector<NestedLevel> nested_ladder(const Config& c)
{
  const CoarseStartOptions o = CoarseStartOptions::from(c);
  const HalfCapSpec cap = HalfCapSpec::from(c);
  if (!o.enabled || !cap.mesh_file.empty()) // the levels are meshes of the parametric cap
    return {};
  const double base = relative_unknowns(o.mesh_size, 1, 0);
  NestedLevel l{cap.mesh_size, cap.order, cap.refinements, 0};
  l.relative_unknowns = relative_unknowns(l.mesh_size, l.order, l.refinements) / base;
  if (l.relative_unknowns < 4.0)
    return {};
  std::vector<NestedLevel> ladder;
  // Intermediate levels for P2 only: from the coarse P1 mesh a P2 Newton
  // wanders at the lower pole, a P1 Newton does not, and an intermediate P1
  // level made a fine P1 solve worse (docs/PERFORMANCE.md, "Figures moved
  // from code comments").
  const int levels = l.order >= 2 ? o.nested_levels : 0;
  for (int k = 0; k < levels; ++k)
  {
    // One step coarser: one uniform refinement fewer (exactly nested), or
    // twice the mesh size.
    if (l.refinements > 0)
      --l.refinements;
    else
      l.mesh_size *= 2;
    l.relative_unknowns = relative_unknowns(l.mesh_size, l.order, l.refinements) / base;
    if (l.relative_unknowns < 4.0)
      break;
    ladder.push_back(l);
  }
  ladder.push_back({o.mesh_size, 1, 0, 1.0});
  std::reverse(ladder.begin(), ladder.end());
  return ladder;
}

bool coarse_start_applies(const Config& c) { return !nested_ladder(c).empty(); }

std::unique_ptr<CoarseStart> make_coarse_start(const Config& c, const Model& fine,
                                               const LevelFactory& make_level)
{
  if (!coarse_start_applies(c))
    return nullptr;
  auto cs = std::make_unique<CoarseStart>(c, fine, make_level);
  std::string levels;
  const auto dofs = cs->level_dofs();
  for (std::size_t k = 0; k < cs->num_levels(); ++k)
    levels += fmt::format("{}{} unknowns ({})", k ? " -> " : "", dofs[k], describe(cs->ladder()[k]));
  log::info("coarse start: {}, set up in {:.2f} s", levels, cs->setup_seconds());
  return cs;
}

// The displacement spaces are isoparametric (forms/common.py: the
// coordinate element is the displacement's Lagrange element of the same
// degree), so the coarse mesh's coordinate element tabulates the coarse
// displacement's basis, with the cell's dofs in the order of its geometry
// nodes (one dof per vertex and per edge: no permutations up to P2).
NodeTransfer::NodeTransfer(const Model& from, const Model& to)
{
  const auto& mesh = *from.mesh().mesh;
  PointLocation loc = locate_points(mesh, to.space()->tabulate_dof_coordinates(false));
  _cells = std::move(loc.cells);
  _moved = loc.moved;
  const auto& cmap = mesh.geometry().cmap();
  const auto shape = cmap.tabulate_shape(0, 1); // (1, 1, nodes, 1)
  const std::size_t n = _cells.size(), nodes = shape[2];
  if (static_cast<std::size_t>(from.space()->dofmap()->cell_dofs(0).size()) != nodes)
    throw std::logic_error("NodeTransfer: the displacement space is not isoparametric");
  _weights.resize(n * nodes);
  std::vector<double> phi(nodes);
  for (std::size_t p = 0; p < n; ++p)
  {
    cmap.tabulate(0, std::span<const double>(loc.reference.data() + 3 * p, 3), {1, 3}, phi);
    std::copy(phi.begin(), phi.end(), _weights.begin() + p * nodes);
  }
}

void NodeTransfer::apply(const Model& from, Model& to) const
{
  // The local values of u are node-major with block size 3, in the order
  // of the tabulated dof coordinates (owned and ghost nodes).
  auto values = to.displacement()->x()->mutable_array();
  const std::size_t n = _cells.size(), nodes = _weights.size() / std::max<std::size_t>(n, 1);
  if (values.size() != 3 * n)
    throw std::logic_error("NodeTransfer: the model is not the one the transfer was built for");
  const auto& dofmap = *from.space()->dofmap();
  const auto coarse = from.displacement()->x()->array();
  for (std::size_t p = 0; p < n; ++p)
  {
    const auto dofs = dofmap.cell_dofs(_cells[p]);
    const double* w = _weights.data() + p * nodes;
    double u[3] = {0, 0, 0};
    for (std::size_t i = 0; i < nodes; ++i)
      for (int d = 0; d < 3; ++d)
        u[d] += w[i] * coarse[3 * dofs[i] + d];
    for (int d = 0; d < 3; ++d)
      values[3 * p + d] = u[d];
  }
  // Constraints exact; the ghost update makes the owners' values win (a node
  // on a coarse face may see two cells).
  to.constrain_displacement();
}

std::unique_ptr<Model> neutral_cap_level(const Config& level_case)
{
  return make_neutral_model(level_case, MPI_COMM_SELF);
}

CoarseStart::CoarseStart(const Config& c, const Model& fine, const LevelFactory& make_level)
    : _ladder(nested_ladder(c)), _load_steps(LoadStepOptions::from(c))
{
  Stopwatch setup("coarse start: set-up");
  if (_ladder.empty())
    throw std::logic_error("CoarseStart: the coarse start does not apply to this case");
  for (const NestedLevel& l : _ladder)
  {
    const Config lc = level_config(c, l);
    Level level;
    double t_model = 0;
    {
      Stopwatch model_clock("coarse start: level model");
      level.model = make_level(lc);
      level.newton = std::make_unique<NewtonSolver>(*level.model, NewtonOptions::from(lc));
      t_model = model_clock.seconds();
    }
    Stopwatch location("coarse start: node location");
    if (!_levels.empty())
      level.from_below = std::make_unique<NodeTransfer>(*_levels.back().model, *level.model);
    log::debug("coarse start, level {} ({}): mesh and model {:.2f} s, node location {:.2f} s",
               _levels.size(), describe(l), t_model, location.seconds());
    _levels.push_back(std::move(level));
  }
  Stopwatch location("coarse start: node location");
  _to_fine = std::make_unique<NodeTransfer>(*_levels.back().model, fine);
  log::debug("coarse start: fine node location {:.2f} s; {} fine nodes outside the finest level's "
             "mesh moved into their cell", location.seconds(), _to_fine->moved());
  _setup_seconds = setup.seconds();
}

CoarseStart::~CoarseStart() = default;

std::vector<std::int64_t> CoarseStart::level_dofs() const
{
  std::vector<std::int64_t> d;
  for (const auto& l : _levels)
    d.push_back(l.model->num_dofs());
  return d;
}

void CoarseStart::transfer_to(Model& fine) const { _to_fine->apply(*_levels.back().model, fine); }

int CoarseStart::solve_from_below(std::size_t k, const std::array<double, 3>& g, std::string& reason)
{
  Level& level = _levels[k];
  Model& m = *level.model;
  const std::string context = fmt::format("coarse start, level {} ({})", k, describe(_ladder[k]));
  const double f = set_gravity(m, g);
  Guess below;
  below.name = "the level below";
  below.set = [&](Model& model, std::string&)
  {
    level.from_below->apply(*_levels[k - 1].model, model);
    return true;
  };
  try
  {
    return solve_at_full_load(m, *level.newton, below, _load_steps, context, f).path.newton_iterations;
  }
  catch (const SolveError& e)
  {
    reason = fmt::format("level {} failed ({})", k, e.what());
    return -1;
  }
}

bool CoarseStart::solve_and_transfer(Model& fine, const std::array<double, 3>& g,
                                     CoarseGuessReport& rep)
{
  // 1. The coarse P1 posture, from its neutral state, with the usual load
  // path; then each level above from the one below.
  Model& coarse = *_levels.front().model;
  coarse.displacement()->x()->set(0.0);
  const double f_coarse = set_gravity(coarse, g);
  try
  {
    LoadPathReport p = continuation(coarse, *_levels.front().newton, "load", 0.0, 1.0, _load_steps,
                                    "coarse start", f_coarse);
    rep.level_newton_iterations.push_back(p.newton_iterations);
    rep.linear_iterations = p.linear_iterations;
  }
  catch (const SolveError& e)
  {
    rep.reason = fmt::format("the coarse solve failed ({})", e.what());
  }
  for (std::size_t k = 1; k < _levels.size() && rep.reason.empty(); ++k)
  {
    const int its = solve_from_below(k, g, rep.reason);
    if (its >= 0)
      rep.level_newton_iterations.push_back(its);
  }
  for (int its : rep.level_newton_iterations)
    rep.newton_iterations += its;
  // Every rank solves the same ladder and should agree; the decision is
  // made collectively all the same (the steps below are).
  int ok = rep.reason.empty() ? 1 : 0, all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, fine.mesh().mesh->comm());
  if (!all_ok)
  {
    if (rep.reason.empty())
      rep.reason = "the coarse solve failed on another rank";
    return false;
  }
  // 2. The finest level's interpolant at the fine nodes.
  transfer_to(fine);
  return true;
}

CoarseGuessReport CoarseStart::guess(Model& fine, const std::array<double, 3>& g)
{
  CoarseGuessReport rep;
  auto& x = *fine.displacement()->x();
  x.set(0.0);
  const double energy_at_rest = fine.energy();
  if (!solve_and_transfer(fine, g, rep))
    return rep;
  rep.reason = inadmissible_guess(fine, energy_at_rest);
  rep.used = rep.reason.empty();
  if (!rep.used)
    x.set(0.0);
  return rep;
}
} // namespace breastsim
