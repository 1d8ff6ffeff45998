// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The forward map of a diagnosis: a case -> the normal distances of the
// recorded points to the simulated deformed skin (surface_distance.hpp) and
// the nipple landmark errors, in every recorded posture, whitened by the
// noise (or by sigma_eff once the numerical noise floor is known). Keeps one
// warm-started ForwardModel.
#include "case_groups.hpp"
#include "config.hpp"
#include "forward_model.hpp"
#include "recording.hpp"
#include <array>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <vector>

namespace breastsim::diagnosis
{
using calibration::ForwardModel;
using calibration::Recording;

/// One forward evaluation: distances of the recorded points, landmark errors.
struct PointEvaluation
{
  std::vector<std::vector<double>> distances;      ///< per posture, per point [m]
  std::vector<std::array<double, 3>> nipple_error; ///< per posture, model - landmark [m] (NaN: none)
  std::vector<double> raw; ///< recording - model [m] (distances, then landmarks)
  std::vector<double> r;   ///< raw / sigma
  /// Per posture: solved (false: excluded or, in try_each, failed; its
  /// distances, landmark errors, raw and r are then 0).
  std::vector<bool> solved;
};

class PointEvaluator
{
public:
  /// On `comm`; with `groups` of more than one (comm = groups->comm()), the
  /// postures are solved side by side, posture i by group i mod groups
  /// (always the same group, so each keeps its posture's warm start as in
  /// serial), and every rank takes all of them (CaseGroups::map).
  PointEvaluator(const Recording& rec, MPI_Comm comm, const CaseGroups* groups = nullptr);
  /// Collective. The evaluation of case `c`; throws SolveError.
  PointEvaluation operator()(const Config& c);
  /// Collective. As operator(), but a posture whose solve fails is marked
  /// unsolved (PointEvaluation::solved) instead of throwing.
  PointEvaluation try_each(const Config& c);
  /// Collective. As try_each, and a posture that was not excluded but fails
  /// is excluded from now on; returns the postures so newly left out.
  std::vector<std::size_t> leave_out_failures(const Config& c, PointEvaluation& e);
  /// Leave posture `i` out of every later evaluation (not solved; its
  /// residuals 0, so it adds nothing to chi2 or to a Jacobian).
  void exclude(std::size_t i) { _excluded.at(i) = true; }
  bool excluded(std::size_t i) const { return _excluded.at(i); }
  /// Solve posture `i` again in later evaluations (undoes exclude).
  void include(std::size_t i) { _excluded.at(i) = false; }

  /// Collective. dr/dy at case `c`, one column per direction (each a
  /// parameter y's cases at y +- h: ForwardModel::CaseDifference), in the
  /// rows of r: each posture's distance derivatives
  /// (calibration::distance_derivatives of du/dy's surface motion), then the
  /// landmarks' (-d nipple/dy), over sigma; an excluded posture's rows are 0.
  /// A posture whose last solve was not at `c` is solved again first.
  /// Throws SolveError.
  std::vector<std::vector<double>> jacobian(const Config& c,
                                            const std::vector<ForwardModel::CaseDifference>& directions);

  /// Posture solves of the evaluations so far, over all groups.
  int posture_solves() const { return _posture_solves; }
  /// Skin surface documents of case `c` per posture (collective; rank 0).
  std::vector<nlohmann::json> surfaces(const Config& c);
  /// Standard deviation of each raw residual from now on [m] (default: the noise sigma).
  void set_sigma(std::vector<double> s) { _sigma = std::move(s); }

private:
  std::vector<double> distances(std::size_t posture, const Model& model) const;
  /// Posture i's "recording - model" [m] at the prepared case `c`: its
  /// distances, then its landmark; all NaN when it is excluded or (with
  /// _tolerant) its solve fails. Throws SolveError.
  std::vector<double> posture_part(std::size_t i, const Config& c);
  /// Posture i's rows of jacobian() before the division by sigma
  /// (row-major, one column per direction; distances, then the landmark).
  std::vector<double> posture_jacobian(std::size_t i, const Config& c,
                                       const std::vector<ForwardModel::CaseDifference>& directions);
  /// Every posture's part, each solved by its group (CaseGroups::map).
  std::vector<std::vector<double>> parts(const Config& c);

  const Recording& _rec;
  MPI_Comm _comm;
  const CaseGroups* _groups;
  ForwardModel _forward;
  std::vector<double> _sigma;
  std::vector<bool> _excluded;
  bool _tolerant = false; ///< inside try_each
  int _posture_solves = 0;
};
} // namespace breastsim::diagnosis
