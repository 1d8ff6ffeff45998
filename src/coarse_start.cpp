#include "coarse_start.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "simulate.hpp"
#include <chrono>
#include <cmath>
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/geometry/utils.h>
#include <fmt/format.h>
#include <mpi.h>
#include <numeric>

namespace breastsim
{
namespace
{
/// The case on the coarse mesh: same geometry and physics, P1, no refinement.
Config coarse_config(const Config& c)
{
  Config cc = c;
  cc.set("geometry.mesh_size", c.number("solver.coarse_mesh_size"));
  cc.set("geometry.order", std::int64_t{1});
  cc.set("geometry.refinements", std::int64_t{0});
  cc.set("solver.linear", std::string("auto"));
  return cc;
}

/// Coarse cell of every point (row-major n x 3, moved where needed): a cell
/// containing it, or else (points just outside the coarse polyhedron, on the
/// curved skin) the nearest cell, and the point is moved to the nearest
/// point of that cell. The coarse field is thus extended constantly along
/// the normal, never extrapolated from a possibly thin cell.
std::vector<std::int32_t> locate(const dolfinx::mesh::Mesh& mesh, std::vector<double>& points)
{
  namespace geo = dolfinx::geometry;
  const std::int32_t ncells = mesh.topology().index_map(3)->size_local();
  std::vector<std::int32_t> all(ncells);
  std::iota(all.begin(), all.end(), 0);
  geo::BoundingBoxTree tree(mesh, 3, all);
  const auto candidates = geo::compute_collisions(tree, points);
  const auto colliding = geo::compute_colliding_cells(mesh, candidates, points);
  const std::size_t n = points.size() / 3;
  std::vector<std::int32_t> cells(n, -1);
  std::vector<std::size_t> outside;
  std::vector<double> outside_points;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (colliding.num_links(i) > 0)
      cells[i] = colliding.links(i)[0];
    else
    {
      outside.push_back(i);
      outside_points.insert(outside_points.end(), points.begin() + 3 * i, points.begin() + 3 * i + 3);
    }
  }
  if (outside.empty())
    return cells;
  geo::BoundingBoxTree midpoints = geo::create_midpoint_tree(mesh, 3, all);
  const auto nearest = geo::compute_closest_entity(tree, midpoints, mesh, outside_points);
  // shortest_vector: from the cell to the point.
  const auto v = geo::shortest_vector(mesh, 3, nearest, outside_points);
  for (std::size_t k = 0; k < outside.size(); ++k)
  {
    cells[outside[k]] = nearest[k];
    for (int d = 0; d < 3; ++d)
      points[3 * outside[k] + d] -= v[3 * k + d];
  }
  return cells;
}
} // namespace

bool coarse_start_applies(const Config& c)
{
  if (!c.flag("solver.coarse_start"))
    return false;
  // Unknowns scale as h^-3, x ~7 for P2 (nodes per vertex of a tet mesh),
  // x 8 per refinement.
  const double ratio = std::pow(c.number("solver.coarse_mesh_size") / c.number("geometry.mesh_size"), 3)
                       * (c.integer("geometry.order") == 2 ? 7.0 : 1.0)
                       * std::pow(8.0, static_cast<double>(c.integer("geometry.refinements")));
  return ratio >= 4.0;
}

std::unique_ptr<CoarseStart> make_coarse_start(const Config& c, const Model& fine)
{
  if (!coarse_start_applies(c))
    return nullptr;
  auto cs = std::make_unique<CoarseStart>(c, fine);
  log::info("coarse start: {} coarse unknowns (mesh size {:g} m, P1), set up in {:.2f} s",
            cs->coarse_dofs(), c.number("solver.coarse_mesh_size"), cs->setup_seconds());
  return cs;
}

CoarseStart::CoarseStart(const Config& c, const Model& fine) : _load_steps(load_step_options(c))
{
  const auto t0 = std::chrono::steady_clock::now();
  const Config cc = coarse_config(c);
  _coarse = std::make_unique<Model>(build_neutral_mesh(cc, MPI_COMM_SELF), fine.constraints());
  apply_parameters(cc, *_coarse);
  _newton = std::make_unique<NewtonSolver>(*_coarse, newton_options(cc));

  _points = fine.space()->tabulate_dof_coordinates(false);
  _cells = locate(*_coarse->mesh().mesh, _points);
  _setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void CoarseStart::transfer_to(Model& fine) const
{
  // The local values of u are node-major with block size 3, like the rows
  // of _points (owned and ghost nodes).
  auto& x = *fine.displacement()->x();
  const std::size_t n = _cells.size();
  auto values = x.mutable_array();
  if (values.size() != 3 * n)
    throw std::logic_error("CoarseStart: the fine model is not the one the transfer was built for");
  _coarse->displacement()->eval(_points, {n, 3}, _cells, values, {n, 3});
  // Constraints exact; the ghost update makes the owners' values win (a node
  // on a coarse face may see two cells).
  fine.constrain_displacement();
}

CoarseGuessReport CoarseStart::guess(Model& fine, const std::array<double, 3>& g)
{
  CoarseGuessReport rep;
  auto& x = *fine.displacement()->x();
  x.set(0.0);
  const double e0 = fine.energy();

  // 1. The coarse posture, from its neutral state, with the usual load path.
  _coarse->displacement()->x()->set(0.0);
  const double f_coarse = set_gravity(*_coarse, g);
  try
  {
    LoadPathReport p = continuation(*_coarse, *_newton, "load", 0.0, 1.0, _load_steps, "coarse start",
                                    f_coarse);
    rep.newton_iterations = p.newton_iterations;
    rep.linear_iterations = p.linear_iterations;
  }
  catch (const SolveError& e)
  {
    rep.reason = fmt::format("the coarse solve failed ({})", e.what());
  }
  // Every rank solves the same coarse problem and should agree; the
  // decision is made collectively all the same (the steps below are).
  int ok = rep.reason.empty() ? 1 : 0, all_ok = 0;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, fine.mesh().mesh->comm());
  if (!all_ok)
  {
    if (rep.reason.empty())
      rep.reason = "the coarse solve failed on another rank";
    return rep;
  }

  // 2. Its interpolant at the fine nodes.
  transfer_to(fine);

  // 3. Use it only if it is admissible and better than the neutral state.
  const double detF = fine.min_detF();
  const double e = detF > 0 ? fine.energy() : std::numeric_limits<double>::quiet_NaN();
  if (!(detF > 0))
    rep.reason = fmt::format("its interpolant inverts a fine element (min det F = {:.3g})", detF);
  else if (!(e < e0))
    rep.reason = fmt::format("its interpolant does not lower the energy ({:.6g} J vs {:.6g} J at u = 0)", e, e0);
  else
  {
    rep.used = true;
    return rep;
  }
  x.set(0.0);
  return rep;
}
} // namespace breastsim
