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

PointEvaluation PointEvaluator::operator()(const Config& c)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t np = _rec.postures.size();
  PointEvaluation e;
  e.distances.resize(np);
  // Residuals "recording - model" [m]: the distances, then the landmarks.
  auto solve_raw = [&]
  {
    auto visit = [&](std::size_t i, const Model& model) { e.distances[i] = distances(i, model); };
    const auto obs = _forward.solve(c, visit);
    std::vector<double> raw;
    for (std::size_t i = 0; i < np; ++i)
      raw.insert(raw.end(), e.distances[i].begin(), e.distances[i].end());
    for (std::size_t i = 0; i < np; ++i)
      if (const auto& n = _rec.postures[i].nipple)
        for (int k = 0; k < 3; ++k)
          raw.push_back((*n)[k] - obs[i].nipple[k]);
    return raw;
  };
  const std::vector<double> raw = _groups ? _groups->replicate(solve_raw) : solve_raw();
  std::size_t j = 0;
  for (std::size_t i = 0; i < np; ++i)
    for (auto& d : e.distances[i])
      d = raw[j++];
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
