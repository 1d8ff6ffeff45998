#pragma once
// The forward map of a calibration: case parameters -> observables in each
// measured posture. Keeps one mesh/model while the neutral shape (R, H) is
// unchanged and warm-starts each posture from its last solution; remeshes
// (and solves from rest) when R or H change.
#include "config.hpp"
#include "newton.hpp"
#include "observables.hpp"
#include "posture.hpp"
#include <functional>
#include <memory>
#include <vector>

namespace breastsim::calibration
{
class ForwardModel
{
public:
  ForwardModel(std::vector<Posture> postures, MPI_Comm comm);
  ~ForwardModel();
  /// Called after each posture's solve with the posture's index and the
  /// solved model (e.g. to read the deformed skin surface).
  using PostureVisitor = std::function<void(std::size_t posture, const Model& model)>;

  /// Observables of each posture (in the order given) for case `c`.
  /// Throws SolveError if a posture cannot be solved.
  std::vector<Observables> solve(const Config& c, const PostureVisitor& visit = {});

  int posture_solves() const { return _posture_solves; }
  int warm_starts() const { return _warm_starts; }
  int meshes_built() const { return _meshes; }
  std::int64_t dofs() const;

private:
  void rebuild(const Config& c);
  Observables solve_one(std::size_t i, const Config& c);

  std::vector<Posture> _postures;
  MPI_Comm _comm;
  double _R = -1, _H = -1, _mesh_size = -1;
  bool _fixed_base = false;
  std::unique_ptr<Model> _model;
  std::unique_ptr<NewtonSolver> _newton;
  std::unique_ptr<ObservableProbe> _probe;
  std::vector<std::vector<T>> _last; ///< last solution of each posture (empty: none yet)
  int _posture_solves = 0, _warm_starts = 0, _meshes = 0;
};
} // namespace breastsim::calibration
