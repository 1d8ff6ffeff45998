// SPDX-License-Identifier: LGPL-3.0-or-later
#include "point_evaluator.hpp"
#include "surface_distance.hpp"
#include "surface_export.hpp"
#include "errors.hpp"
#include "log.hpp"
#include <algorithm>
#include <cmath>
#include <limits>

namespace breastsim::diagnosis
{
namespace
{
std::vector<Posture> postures(const Recording& rec)
{
  std::vector<Posture> p;
  for (const auto& q : rec.postures)
    p.push_back({q.name, q.theta_deg});
  return p;
}
} // namespace

PointEvaluator::PointEvaluator(const Recording& rec, MPI_Comm comm, const CaseGroups* groups)
    : _rec(rec), _comm(comm), _groups(groups), _forward(postures(rec), comm),
      _excluded(rec.postures.size(), false)
{
}

std::vector<nlohmann::json> PointEvaluator::surfaces(const Config& c)
{
  _posture_solves += static_cast<int>(_rec.postures.size());
  return _forward.surfaces(c);
}

std::vector<double> PointEvaluator::distances(std::size_t i, const Model& model) const
{
  int rank;
  MPI_Comm_rank(_comm, &rank);
  const SkinSurface s = gather_skin_surface(model); // complete on rank 0
  std::vector<double> d(_rec.postures[i].points.size(), 0.0);
  if (rank == 0)
  {
    const auto m = calibration::match_points(s, _rec.postures[i].points);
    for (std::size_t k = 0; k < m.size(); ++k)
      d[k] = m[k].distance;
  }
  MPI_Bcast(d.data(), static_cast<int>(d.size()), MPI_DOUBLE, 0, _comm);
  return d;
}

std::vector<double> PointEvaluator::posture_part(std::size_t i, const Config& c)
{
  const auto& posture = _rec.postures[i];
  const std::vector<double> unsolved(posture.points.size() + (posture.nipple ? 3 : 0),
                                     std::numeric_limits<double>::quiet_NaN());
  if (_excluded[i])
    return unsolved;
  std::vector<double> part;
  try
  {
    const Observables obs = _forward.solve_posture(
        i, c, [&](std::size_t, const Model& model) { part = distances(i, model); });
    if (const auto& n = posture.nipple)
      for (int k = 0; k < 3; ++k)
        part.push_back((*n)[k] - obs.nipple[k]);
  }
  catch (const SolveError& err)
  {
    if (!_tolerant)
      throw;
    log::warn_on(_comm, "posture '{}' not solved: {}", posture.name, err.what()); // from its group
    return unsolved;
  }
  return part;
}

std::vector<std::vector<double>> PointEvaluator::parts(const Config& c)
{
  const std::size_t np = _rec.postures.size();
  _forward.prepare(c);
  const auto part = [&](std::size_t i) { return posture_part(i, c); };
  if (_groups && _groups->groups() > 1)
    return _groups->map(np, part);
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < np; ++i)
    out.push_back(part(i));
  return out;
}

PointEvaluation PointEvaluator::operator()(const Config& c)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto all = parts(c);
  PointEvaluation e;
  std::vector<double> landmarks;
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    const auto& posture = _rec.postures[i];
    const auto n = static_cast<std::ptrdiff_t>(posture.points.size());
    const bool solved = all[i].empty() || !std::isnan(all[i][0]);
    const std::vector<double> part = solved ? all[i] : std::vector<double>(all[i].size(), 0.0);
    e.solved.push_back(solved);
    e.distances.emplace_back(part.begin(), part.begin() + n);
    e.raw.insert(e.raw.end(), part.begin(), part.begin() + n);
    std::array<double, 3> err = {nan, nan, nan};
    if (posture.nipple)
      for (int k = 0; k < 3; ++k)
      {
        err[k] = -part[n + k]; // model - landmark
        landmarks.push_back(part[n + k]);
      }
    e.nipple_error.push_back(err);
    _posture_solves += _excluded[i] ? 0 : 1;
  }
  // "recording - model": all distances first, then the landmarks.
  e.raw.insert(e.raw.end(), landmarks.begin(), landmarks.end());
  for (std::size_t k = 0; k < e.raw.size(); ++k)
    e.r.push_back(e.raw[k] / (_sigma.empty() ? _rec.noise_sigma : _sigma[k]));
  return e;
}

std::vector<double> PointEvaluator::posture_jacobian(
    std::size_t i, const Config& c, const std::vector<ForwardModel::CaseDifference>& directions)
{
  const auto& posture = _rec.postures[i];
  const std::size_t n = posture.points.size(), nd = directions.size();
  std::vector<double> block((n + (posture.nipple ? 3 : 0)) * nd, 0.0);
  if (_excluded[i])
    return block;
  int rank;
  MPI_Comm_rank(_comm, &rank);
  SkinSurface s;
  std::vector<calibration::SurfaceMatch> matches;
  auto column = [&](std::size_t j, const Model& model, std::span<const double> du,
                    const Observables& d_obs)
  {
    if (j == 0) // the equilibrium's surface and matches, as in distances()
    {
      s = gather_skin_surface(model);
      if (rank == 0)
        matches = calibration::match_points(s, posture.points);
    }
    const SkinSurface moved = gather_skin_surface(model, du); // reference + du
    std::vector<double> dd(n, 0.0);
    if (rank == 0)
    {
      std::vector<calibration::Point> velocity(moved.deformed.size());
      for (std::size_t v = 0; v < velocity.size(); ++v)
        for (int k = 0; k < 3; ++k)
          velocity[v][k] = moved.deformed[v][k] - moved.reference[v][k];
      dd = calibration::distance_derivatives(s, posture.points, matches, velocity);
    }
    MPI_Bcast(dd.data(), static_cast<int>(n), MPI_DOUBLE, 0, _comm);
    for (std::size_t k = 0; k < n; ++k)
      block[k * nd + j] = dd[k];
    if (posture.nipple) // raw = landmark - nipple
      for (int k = 0; k < 3; ++k)
        block[(n + k) * nd + j] = -d_obs.nipple[k];
  };
  _forward.sensitivities(i, c, directions, column);
  return block;
}

std::vector<std::vector<double>> PointEvaluator::jacobian(
    const Config& c, const std::vector<ForwardModel::CaseDifference>& directions)
{
  const std::size_t np = _rec.postures.size(), nd = directions.size();
  const auto part = [&](std::size_t i) { return posture_jacobian(i, c, directions); };
  std::vector<std::vector<double>> blocks;
  if (_groups && _groups->groups() > 1)
    blocks = _groups->map(np, part);
  else
    for (std::size_t i = 0; i < np; ++i)
      blocks.push_back(part(i));
  // Rows as in operator(): all distances first, then the landmarks.
  std::vector<std::vector<double>> J, landmarks;
  for (std::size_t i = 0; i < np; ++i)
  {
    const std::size_t n = _rec.postures[i].points.size(), rows = blocks[i].size() / std::max<std::size_t>(nd, 1);
    for (std::size_t k = 0; k < rows; ++k)
      (k < n ? J : landmarks)
          .emplace_back(blocks[i].begin() + k * nd, blocks[i].begin() + (k + 1) * nd);
  }
  J.insert(J.end(), landmarks.begin(), landmarks.end());
  for (std::size_t k = 0; k < J.size(); ++k)
    for (double& x : J[k])
      x /= _sigma.empty() ? _rec.noise_sigma : _sigma[k];
  return J;
}

PointEvaluation PointEvaluator::try_each(const Config& c)
{
  struct Tolerant
  {
    bool& flag;
    explicit Tolerant(bool& f) : flag(f) { flag = true; }
    ~Tolerant() { flag = false; }
  } tolerant(_tolerant);
  return (*this)(c);
}

std::vector<std::size_t> PointEvaluator::leave_out_failures(const Config& c, PointEvaluation& e)
{
  e = try_each(c);
  std::vector<std::size_t> lost;
  for (std::size_t i = 0; i < e.solved.size(); ++i)
    if (!e.solved[i] && !_excluded[i])
    {
      _excluded[i] = true;
      lost.push_back(i);
    }
  return lost;
}
} // namespace breastsim::diagnosis
