#include "point_evaluator.hpp"
#include "surface_distance.hpp"
#include "surface_export.hpp"
#include <limits>

namespace breastsim::calibration
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
    : _rec(rec), _comm(comm), _groups(groups), _forward(postures(rec), comm)
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
    const auto m = match_points(s, _rec.postures[i].points);
    for (std::size_t k = 0; k < m.size(); ++k)
      d[k] = m[k].distance;
  }
  MPI_Bcast(d.data(), static_cast<int>(d.size()), MPI_DOUBLE, 0, _comm);
  return d;
}

std::vector<double> PointEvaluator::raw_residuals(const Config& c, PointEvaluation& e)
{
  const std::size_t np = _rec.postures.size();
  // Posture i's part, "recording - model" [m]: its distances, then its landmark.
  auto posture_raw = [&](std::size_t i, const Observables& obs)
  {
    std::vector<double> raw = e.distances[i];
    if (const auto& n = _rec.postures[i].nipple)
      for (int k = 0; k < 3; ++k)
        raw.push_back((*n)[k] - obs.nipple[k]);
    return raw;
  };
  auto visit = [&](std::size_t i, const Model& model) { e.distances[i] = distances(i, model); };
  std::vector<std::vector<double>> parts(np);
  if (_groups && _groups->groups() > 1)
  {
    _forward.prepare(c);
    parts = _groups->map(np, [&](std::size_t i)
                         { return posture_raw(i, _forward.solve_posture(i, c, visit)); });
  }
  else
  {
    const auto obs = _forward.solve(c, visit);
    for (std::size_t i = 0; i < np; ++i)
      parts[i] = posture_raw(i, obs[i]);
  }
  _posture_solves += static_cast<int>(np);
  // All distances first, then the landmarks, posture by posture.
  std::vector<double> raw, landmarks;
  for (std::size_t i = 0; i < np; ++i)
  {
    const std::size_t n = _rec.postures[i].points.size();
    raw.insert(raw.end(), parts[i].begin(), parts[i].begin() + static_cast<std::ptrdiff_t>(n));
    landmarks.insert(landmarks.end(), parts[i].begin() + static_cast<std::ptrdiff_t>(n),
                     parts[i].end());
  }
  raw.insert(raw.end(), landmarks.begin(), landmarks.end());
  return raw;
}

PointEvaluation PointEvaluator::operator()(const Config& c)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t np = _rec.postures.size();
  PointEvaluation e;
  e.distances.resize(np);
  const std::vector<double> raw = raw_residuals(c, e);
  std::size_t j = 0;
  for (std::size_t i = 0; i < np; ++i)
  {
    e.distances[i].resize(_rec.postures[i].points.size());
    for (auto& d : e.distances[i])
      d = raw[j++];
  }
  for (std::size_t i = 0; i < np; ++i)
  {
    std::array<double, 3> err = {nan, nan, nan};
    if (_rec.postures[i].nipple)
      for (int k = 0; k < 3; ++k)
        err[k] = -raw[j++]; // model - landmark
    e.nipple_error.push_back(err);
  }
  e.raw = raw;
  for (std::size_t k = 0; k < raw.size(); ++k)
    e.r.push_back(raw[k] / (_sigma.empty() ? _rec.noise_sigma : _sigma[k]));
  return e;
}
} // namespace breastsim::calibration
