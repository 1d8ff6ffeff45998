// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Grid sequencing (nested iteration) for the posture solves: solve the same
// case on a ladder of coarser meshes first, each level started from the
// interpolant of the one below, and start the fine Newton iteration from
// the interpolant of the finest of them.
//
// Level 0 is a coarse P1 mesh (solver.coarse_mesh_size), solved from u = 0
// with the load ramp. Above it, for P2 cases, up to solver.nested_levels
// intermediate P2 meshes, each with twice the mesh size of the next finer
// one (or, for a uniformly refined case, one refinement fewer), kept while
// they have at least 4x the coarse unknowns.
//
// Why: Newton's iteration count from u = 0 grows with the mesh; most of the
// iterations are spent far from the solution, where each one costs a fine
// Jacobian and a fine linear solve. The coarse P1 problem finds the large
// deformation for a fraction of that cost. For P2 that is not enough: from
// it the fine Newton still wanders for a dozen iterations at the lower pole
// near the base rim, where the P2 solution has features the coarse P1 one
// lacks; from a P2 solution at twice the mesh size that phase is gone (all
// full steps). Iteration counts: docs/PERFORMANCE.md, "Figures moved from
// code comments".
//
// Every level is built and solved on MPI_COMM_SELF on every rank: each rank
// evaluates the level below at its own nodes (owned and ghost), so the
// initial guess is the same for any partition (the levels' cost is not
// shared between ranks). Nodes outside the coarser mesh (the curved skin)
// take the value at the nearest point of their nearest cell.
#include "config.hpp"
#include "load_stepping.hpp"
#include "model.hpp"
#include "newton.hpp"
#include <functional>
#include <memory>

namespace breastsim
{
/// One mesh of the ladder: its mesh size, element order and uniform
/// refinements, and its estimated unknowns relative to the coarse P1 mesh.
struct NestedLevel
{
  double mesh_size = 0;
  int order = 1;
  int refinements = 0;
  double relative_unknowns = 1;
};

/// Relative unknowns of a mesh (h, order, refinements): h^-3, x ~7 for P2
/// (nodes per vertex of a tetrahedral mesh), x 8 per refinement.
double relative_unknowns(double mesh_size, int order, int refinements);

/// The ladder below the case's mesh, coarse to fine: the coarse P1 mesh,
/// then the intermediate meshes (at most solver.nested_levels of them).
/// Empty when the coarse start does not apply (solver.coarse_start off, or
/// the case's mesh has fewer than 4x the coarse unknowns).
std::vector<NestedLevel> nested_ladder(const Config& c);

/// Whether the coarse start applies: nested_ladder(c) is not empty.
bool coarse_start_applies(const Config& c);

/// Builds the model of one level on MPI_COMM_SELF from the case as seen on
/// that level (geometry.mesh_size, geometry.order, geometry.refinements and
/// the solver keys of the level set), with the case's parameters bound.
using LevelFactory = std::function<std::unique_ptr<Model>(const Config& level_case)>;
/// The levels of the neutral half cap (make_neutral_model on MPI_COMM_SELF).
std::unique_ptr<Model> neutral_cap_level(const Config& level_case);

class CoarseStart;
/// The coarse start of `fine` if coarse_start_applies(c), else nullptr
/// (its levels and set-up time are logged).
std::unique_ptr<CoarseStart> make_coarse_start(const Config& c, const Model& fine,
                                               const LevelFactory& make_level = neutral_cap_level);

struct CoarseGuessReport
{
  bool used = false;          ///< the fine displacement was set from the ladder's solution
  /// Newton iterations on each level (coarse first), and their sum.
  std::vector<int> level_newton_iterations;
  int newton_iterations = 0;
  int linear_iterations = 0;
  std::string reason;         ///< why it was not used (if so)
};

/// Where each local node (owned and ghost) of a finer space takes the
/// displacement of a coarser model, and the transfer itself.
class NodeTransfer
{
public:
  /// Locate every local node of `to` in the mesh of `from` (local, no
  /// communication).
  NodeTransfer(const Model& from, const Model& to);
  /// Set to's displacement to the interpolant of from's, with to's
  /// constraints applied (ghosts updated).
  void apply(const Model& from, Model& to) const;
  /// Nodes that were outside every coarse cell and moved into the nearest one.
  std::size_t moved() const { return _moved; }

private:
  std::vector<std::int32_t> _cells;  ///< coarse cell of each node
  /// The coarse cell's basis functions at each node (n x nodes per cell):
  /// u(x) = sum_i phi_i(X) u_i, X the node's reference point in the cell.
  std::vector<double> _weights;
  std::size_t _moved = 0;
};

class CoarseStart
{
public:
  /// Build every level of nested_ladder(c) with `make_level` and locate the
  /// nodes of each level (and of `fine`) in the level below.
  CoarseStart(const Config& c, const Model& fine, const LevelFactory& make_level = neutral_cap_level);
  ~CoarseStart();

  /// Solve the ladder under gravity g (full load): the coarse P1 level from
  /// u = 0 with the case's load stepping, each level above from the
  /// interpolant of the one below (solve_at_full_load: Newton if that
  /// interpolant is admissible, else or if Newton fails from it the load
  /// ramp from u = 0). Then set the fine displacement to the interpolant of
  /// the finest level, with the fine constraints applied. False (fine
  /// displacement untouched, reason in `rep`) if a level fails on any rank.
  /// Collective on the fine communicator.
  bool solve_and_transfer(Model& fine, const std::array<double, 3>& g, CoarseGuessReport& rep);

  /// solve_and_transfer from u = 0 at the fine model's current load, then
  /// the check of every guess (inadmissible_guess, warm_start.hpp): not used
  /// (fine displacement left at 0) if the interpolant inverts a fine element
  /// or does not lower the fine energy below that of u = 0. Collective.
  CoarseGuessReport guess(Model& fine, const std::array<double, 3>& g);

  /// Set the fine displacement to the interpolant of the finest level's
  /// current displacement (constraints applied). Local.
  void transfer_to(Model& fine) const;

  /// The coarse P1 model (level 0) and the finest level's model.
  Model& coarse_model() { return *_levels.front().model; }
  Model& finest_level_model() { return *_levels.back().model; }
  /// Number of levels (coarse P1 plus intermediate).
  std::size_t num_levels() const { return _levels.size(); }
  /// The ladder and the unknowns of each level.
  const std::vector<NestedLevel>& ladder() const { return _ladder; }
  std::vector<std::int64_t> level_dofs() const;
  std::int64_t coarse_dofs() const { return _levels.front().model->num_dofs(); }
  /// Wall time of the constructor (meshes, models, node location) [s].
  double setup_seconds() const { return _setup_seconds; }

private:
  struct Level
  {
    std::unique_ptr<Model> model;
    std::unique_ptr<NewtonSolver> newton;
    std::unique_ptr<NodeTransfer> from_below; ///< level k-1 -> k (none for level 0)
  };
  /// Solve level k (k >= 1) from the interpolant of level k-1: its Newton
  /// iterations, or -1 (reason set) if it fails.
  int solve_from_below(std::size_t k, const std::array<double, 3>& g, std::string& reason);
  std::vector<NestedLevel> _ladder;
  std::vector<Level> _levels;
  std::unique_ptr<NodeTransfer> _to_fine;
  LoadStepOptions _load_steps;
  double _setup_seconds = 0;
};
} // namespace breastsim
