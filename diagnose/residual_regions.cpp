// SPDX-License-Identifier: LGPL-3.0-or-later
#include "residual_regions.hpp"
#include "geometry_options.hpp"
#include "point_neighbours.hpp"
#include <algorithm>
#include <cmath>
#include <deque>
#include <fmt/format.h>
#include <stdexcept>

namespace breastsim::diagnosis
{
namespace
{
/// Same-sign points beyond |z| = region_z connected through neighbourhoods,
/// grown from `seed` (labelled in `label`).
std::vector<std::size_t> cluster(std::size_t seed, const std::vector<double>& z, const Neighbours& knn,
                                 double region_z, std::vector<int>& label)
{
  const double sign = z[seed] > 0 ? 1 : -1;
  std::vector<std::size_t> members;
  std::deque<std::size_t> queue = {seed};
  label[seed] = static_cast<int>(seed);
  while (!queue.empty())
  {
    const std::size_t i = queue.front();
    queue.pop_front();
    members.push_back(i);
    for (auto j : knn[i])
      if (label[j] < 0 && sign * z[j] >= region_z)
      {
        label[j] = static_cast<int>(seed);
        queue.push_back(j);
      }
  }
  return members;
}

std::string where_text(const Point& c, const std::array<double, 3>& nipple, double R)
{
  const double dz = c[2] - nipple[2];
  std::string vertical = dz > 0.01 ? "upper pole" : (dz < -0.01 ? "lower pole" : "at nipple height");
  std::string depth = c[1] > 0.75 * nipple[1] ? "around the nipple-areola"
                      : (c[1] < 0.3 * nipple[1] ? "near the chest wall" : "mid-breast");
  std::string side = c[0] < 0.25 * R ? "close to the nipple's sagittal plane"
                                     : fmt::format("{:.0f} mm off the nipple's sagittal plane", 1e3 * c[0]);
  return fmt::format("{}, {}, {}", vertical, depth, side);
}

/// The model nipple of posture p: landmark + error; without a landmark, the
/// most projected recorded point.
std::array<double, 3> model_nipple(const Recording& rec, const FitState& f, std::size_t p)
{
  const auto& pts = rec.postures[p].points;
  const auto& ne = f.nipple_error[p];
  std::array<double, 3> nipple = {0, 0, 0};
  if (rec.postures[p].nipple && std::isfinite(ne[0]))
    for (int c = 0; c < 3; ++c)
      nipple[c] = (*rec.postures[p].nipple)[c] + ne[c];
  else
    nipple = *std::max_element(pts.begin(), pts.end(),
                               [](const Point& a, const Point& b) { return a[1] < b[1]; });
  return nipple;
}

/// The region of posture p made of the flagged `members` and their neighbourhoods.
Region make_region(const Recording& rec, const FitState& f, std::size_t p, const double* w,
                   const std::vector<std::size_t>& members, const Neighbours& knn, double R)
{
  const auto& pts = rec.postures[p].points;
  const auto& d = f.distances[p];
  const std::size_t n = pts.size();
  std::vector<char> in(n, 0);
  for (auto i : members)
  {
    in[i] = 1;
    for (auto j : knn[i])
      in[j] = 1;
  }
  Region r;
  r.posture = rec.postures[p].name;
  double sum_r = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (in[i])
    {
      ++r.points;
      for (int c = 0; c < 3; ++c)
        r.centroid[c] += pts[i][c];
      r.mean_residual += d[i];
      r.max_residual = std::max(r.max_residual, std::abs(d[i]));
      sum_r += w[i];
    }
  for (int c = 0; c < 3; ++c)
    r.centroid[c] /= r.points;
  r.mean_residual /= r.points;
  r.z = sum_r / std::sqrt(static_cast<double>(r.points));
  r.where = where_text(r.centroid, model_nipple(rec, f, p), R);
  return r;
}
} // namespace

std::vector<Region> locate_regions(const Recording& rec, const FitState& f, int neighbours,
                                   double region_z)
{
  std::vector<Region> regions;
  const double R = HalfCapSpec::from(f.config).R;
  std::size_t first_row = 0; // f.r: the points of every posture in order, then the landmarks
  for (std::size_t p = 0; p < rec.postures.size(); ++p)
  {
    const auto& pts = rec.postures[p].points;
    const std::size_t n = pts.size();
    if (f.r.size() < first_row + n)
      throw std::logic_error("locate_regions: the fit has fewer residuals than recorded points");
    const double* w = f.r.data() + first_row; // d_i / sigma_eff,i
    first_row += n;
    const int k = std::min<int>(neighbours, static_cast<int>(n) - 1);
    const Neighbours knn = nearest_neighbours(pts, k);
    // Neighbourhood z: sum of k + 1 whitened residuals / sqrt(k + 1) ~ N(0, 1) for noise.
    std::vector<double> z(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      double s = w[i];
      for (auto j : knn[i])
        s += w[j];
      z[i] = s / std::sqrt(k + 1.0);
    }
    std::vector<int> label(n, -1);
    for (std::size_t seed = 0; seed < n; ++seed)
    {
      if (label[seed] >= 0 || std::abs(z[seed]) < region_z)
        continue;
      const auto members = cluster(seed, z, knn, region_z, label);
      if (members.size() >= 3)
        regions.push_back(make_region(rec, f, p, w, members, knn, R));
    }
  }
  std::sort(regions.begin(), regions.end(),
            [](const Region& a, const Region& b) { return std::abs(a.z) > std::abs(b.z); });
  return regions;
}
} // namespace breastsim::diagnosis
