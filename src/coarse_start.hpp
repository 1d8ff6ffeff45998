#pragma once
// Grid sequencing for the posture solves: solve the same case on a coarse P1
// mesh first and start the fine Newton iteration from the coarse solution
// interpolated at the fine nodes.
//
// Newton's iteration count from u = 0 grows with the mesh (10, 14, 22
// iterations at 5k, 50k, 200k tetrahedra, docs/PERFORMANCE.md): most of them
// are spent far from the solution, where each one costs a fine Jacobian and
// a fine linear solve. The coarse problem finds the large deformation for a
// fraction of that cost; on the fine mesh only the local corrections are
// left (the quadratic phase).
//
// The coarse mesh is built and solved on MPI_COMM_SELF on every rank (it is
// small): each rank then evaluates it at its own fine nodes, so the initial
// guess is the same for any partition. Fine nodes outside the coarse
// polyhedron (the curved skin) take the value at the nearest coarse point.
#include "config.hpp"
#include "load_stepping.hpp"
#include "model.hpp"
#include "newton.hpp"
#include <memory>

namespace breastsim
{
/// Whether the case's mesh is fine enough for a coarse start to pay: at
/// least 4x the unknowns of the coarse P1 mesh (estimated from the mesh
/// sizes, the element order and the refinements), and the key is on.
bool coarse_start_applies(const Config& c);

class CoarseStart;
/// The coarse start of `fine` if coarse_start_applies(c), else nullptr
/// (its size and set-up time are logged).
std::unique_ptr<CoarseStart> make_coarse_start(const Config& c, const Model& fine);

struct CoarseGuessReport
{
  bool used = false;          ///< the fine displacement was set from the coarse solution
  int newton_iterations = 0;  ///< on the coarse mesh
  int linear_iterations = 0;
  std::string reason;         ///< why it was not used (if so)
};

class CoarseStart
{
public:
  /// Mesh the case's geometry with solver.coarse_mesh_size (P1, no
  /// refinement) on MPI_COMM_SELF, bind the case's parameters, and locate
  /// every local fine node (owned and ghost) of `fine` in it.
  CoarseStart(const Config& c, const Model& fine);

  /// Solve the coarse model under gravity g (full load) from u = 0 with the
  /// case's load stepping and set the fine displacement to its interpolant,
  /// with the fine constraints applied. Not used (fine displacement left at
  /// 0) if the coarse solve fails or the interpolant inverts an element or
  /// does not lower the fine energy (at its current load) below that of
  /// u = 0. Collective on the fine communicator.
  CoarseGuessReport guess(Model& fine, const std::array<double, 3>& g);

  /// Set the fine displacement to the interpolant of the coarse model's
  /// current displacement, with the fine constraints applied (ghosts
  /// updated). Local: every rank holds the whole coarse model.
  void transfer_to(Model& fine) const;

  /// The coarse model (on MPI_COMM_SELF).
  Model& coarse_model() { return *_coarse; }
  std::int64_t coarse_dofs() const { return _coarse->num_dofs(); }
  /// Wall time of the constructor (coarse mesh, model, node location) [s].
  double setup_seconds() const { return _setup_seconds; }

private:
  std::unique_ptr<Model> _coarse;
  std::unique_ptr<NewtonSolver> _newton;
  LoadStepOptions _load_steps;
  double _setup_seconds = 0;
  std::vector<double> _points;       ///< where each fine node takes the coarse field (n x 3)
  std::vector<std::int32_t> _cells;  ///< coarse cell of each fine node
};
} // namespace breastsim
