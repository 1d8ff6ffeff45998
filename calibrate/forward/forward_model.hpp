// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The forward map of a calibration: case parameters -> observables in each
// measured posture. Keeps one mesh/model and warm-starts each posture from
// its last solution. When the neutral shape (R, H) changes, the mesh built
// for the first shape is morphed onto the new cap (src/mesh/cap_morph.hpp:
// same topology, node positions analytic in R, H), so the observables are
// smooth in R and H; with `morph = false` it is remeshed by gmsh instead
// (and solved from rest). A change of mesh size, order or refinements
// always remeshes.
#include "config.hpp"
#include "newton.hpp"
#include "observables.hpp"
#include "petsc.hpp"
#include "posture.hpp"
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace breastsim::calibration
{
class ForwardModel
{
public:
  ForwardModel(std::vector<Posture> postures, MPI_Comm comm, bool morph = true);
  ~ForwardModel();
  /// Called after each posture's solve with the posture's index and the
  /// solved model (e.g. to read the deformed skin surface).
  using PostureVisitor = std::function<void(std::size_t posture, const Model& model)>;

  /// Observables of each posture (in the order given) for case `c`.
  /// Throws SolveError if a posture cannot be solved.
  std::vector<Observables> solve(const Config& c);
  /// The parts of solve: set up the mesh and the parameters of case `c`
  /// (collective), then solve posture `i` alone (its own warm start).
  void prepare(const Config& c);
  Observables solve_posture(std::size_t i, const Config& c, const PostureVisitor& visit = {});
  /// A direction of differentiation of one parameter y: the cases at
  /// y + h and y - h, which differ from the case only in runtime parameters
  /// (same_mesh), and their distance 2h:  dR/dy = (R(plus) - R(minus)) / width.
  struct CaseDifference
  {
    Config plus, minus;
    double width = 0;
  };
  /// Called with each direction's index, the model at the equilibrium, du/dy
  /// (local and ghost dofs, the layout of displacement()->x()) and the
  /// observables' derivatives along it (ObservableProbe::derivative).
  using SensitivityVisitor = std::function<void(std::size_t direction, const Model& model,
                                                std::span<const double> du,
                                                const Observables& d_observables)>;
  /// Whether cases `a` and `b` are solved on the same mesh (no rebuild and
  /// no morph between them): the condition for a CaseDifference.
  static bool same_mesh(const Config& a, const Config& b);
  /// Sensitivities of posture `i` at the equilibrium of case `c`: at
  /// equilibrium R(u, y) = 0, so
  ///   K du/dy = -dR/dy   (K the tangent at the converged state),
  /// dR/dy from each direction's residual difference, du/dy = 0 on the
  /// Dirichlet dofs. One factorisation per call, one linear solve per
  /// direction. Posture `i` is solved first unless its last solve was at
  /// `c`. Collective; throws SolveError.
  void sensitivities(std::size_t i, const Config& c, const std::vector<CaseDifference>& directions,
                     const SensitivityVisitor& visit);
  /// The direction of number key `key` at case `c`: c with the key at
  /// p +- h, h = 1e-4 |p| (1e-4 at p = 0); none if the key is bound to no
  /// UFL Constant or its neighbouring cases move the mesh (same_mesh: R, H).
  static std::optional<CaseDifference> key_difference(const Config& c, const std::string& key);
  /// d observables / d p of posture `i` at case `c`, one Observables (of
  /// derivatives) per key in `keys` (each with a key_difference; throws
  /// std::logic_error otherwise), by central residual differences of
  /// relative step 1e-4 (exact for parameters entering linearly, O(1e-8)
  /// otherwise). Collective.
  std::vector<Observables> sensitivities(std::size_t i, const Config& c,
                                         const std::vector<std::string>& keys);
  /// The skin surface document (surface_export.hpp) of each posture at case
  /// `c`, for pictures: a posture last solved at `c` is not solved again. Collective; complete on rank 0.
  std::vector<nlohmann::json> surfaces(const Config& c);

  int posture_solves() const { return _posture_solves; }
  int warm_starts() const { return _warm_starts; }
  int meshes_built() const { return _meshes; }
  int morphs() const { return _morphs; }
  std::int64_t dofs() const;
  const std::vector<Posture>& postures() const { return _postures; }

private:
  void rebuild(const Config& c);
  void morph(double R, double H);
  void attach_solver(const Config& c);
  Observables solve_one(std::size_t i, const Config& c);
  /// Model at the equilibrium of posture i for case c (solved if its last
  /// solution is not at c), gravity of the posture at full load.
  void restore_equilibrium(std::size_t i, const Config& c);

  std::vector<Posture> _postures;
  MPI_Comm _comm;
  bool _morph;
  double _R = -1, _H = -1;            ///< current neutral shape of the mesh
  double _R0 = -1, _H0 = -1;          ///< shape the mesh was generated for
  double _nipple_z = 0;               ///< z of the nipple node (a user mesh's; 0 on the cap)
  std::vector<double> _X0;            ///< geometry nodes as generated (local, (n, 3))
  double _mesh_size = -1;
  int _order = -1, _refinements = -1;
  bool _fixed_base = false;
  std::unique_ptr<Model> _model;
  std::unique_ptr<NewtonSolver> _newton;
  std::unique_ptr<ObservableProbe> _probe;
  std::vector<std::vector<T>> _last; ///< last solution of each posture (empty: none yet)
  std::vector<nlohmann::json> _solved_at; ///< the case of each posture's last solution
  /// du/dp of each posture's last solution along the parameters of its last
  /// sensitivities (ForwardModel::sensitivities by key): the next solve at
  /// nearby values of those parameters starts from the first-order
  /// predictor u + sum_j du/dp_j (p'_j - p_j).
  struct Tangent
  {
    Config at; ///< the case of the solution it was taken at
    std::vector<std::string> keys;
    std::vector<std::vector<T>> du;
  };
  std::vector<Tangent> _tangent;
  /// The predictor's step sum_j du/dp_j (p'_j - p_j) for posture i at case
  /// c, or empty when c differs from the last solution's case in anything
  /// but the tangent's parameters.
  std::vector<T> predictor_step(std::size_t i, const Config& c) const;
  int _posture_solves = 0, _warm_starts = 0, _meshes = 0, _morphs = 0;
};
} // namespace breastsim::calibration
