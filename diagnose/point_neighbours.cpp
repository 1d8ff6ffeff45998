// SPDX-License-Identifier: LGPL-3.0-or-later
#include "point_neighbours.hpp"
#include <algorithm>
#include <cmath>

namespace breastsim::diagnosis
{
Neighbours nearest_neighbours(const std::vector<Point>& pts, int k)
{
  const std::size_t n = pts.size();
  Neighbours knn(n);
  std::vector<std::pair<double, std::size_t>> dist;
  for (std::size_t i = 0; i < n; ++i)
  {
    dist.clear();
    for (std::size_t j = 0; j < n; ++j)
      if (j != i)
      {
        double s = 0;
        for (int c = 0; c < 3; ++c)
          s += std::pow(pts[i][c] - pts[j][c], 2);
        dist.push_back({s, j});
      }
    std::partial_sort(dist.begin(), dist.begin() + k, dist.end());
    for (int m = 0; m < k; ++m)
      knn[i].push_back(dist[m].second);
  }
  return knn;
}

std::vector<double> neighbourhood_rms(const std::vector<double>& v, const Neighbours& knn)
{
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    double s = v[i] * v[i];
    for (auto j : knn[i])
      s += v[j] * v[j];
    out[i] = std::sqrt(s / static_cast<double>(knn[i].size() + 1));
  }
  return out;
}
} // namespace breastsim::diagnosis
