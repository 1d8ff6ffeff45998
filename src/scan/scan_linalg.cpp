// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_linalg.hpp"
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace breastsim::scan
{
Eigen3 symmetric_eigen(std::array<double, 9> a)
{
  std::array<double, 9> v = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = a[1] * a[1] + a[2] * a[2] + a[5] * a[5];
    if (off <= 1e-30 * (a[0] * a[0] + a[4] * a[4] + a[8] * a[8]) || off == 0)
      break;
    for (auto [p, q] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}})
    {
      const double apq = a[3 * p + q];
      if (apq == 0)
        continue;
      // Jacobi rotation zeroing a_pq: tan(2 phi) = 2 a_pq / (a_qq - a_pp)
      const double theta = (a[3 * q + q] - a[3 * p + p]) / (2 * apq);
      const double t = (theta >= 0 ? 1 : -1) / (std::abs(theta) + std::sqrt(theta * theta + 1));
      const double c = 1 / std::sqrt(t * t + 1), s = t * c;
      for (int k = 0; k < 3; ++k) // a <- a J
      {
        const double akp = a[3 * k + p], akq = a[3 * k + q];
        a[3 * k + p] = c * akp - s * akq;
        a[3 * k + q] = s * akp + c * akq;
      }
      for (int k = 0; k < 3; ++k) // a <- J^T a
      {
        const double apk = a[3 * p + k], aqk = a[3 * q + k];
        a[3 * p + k] = c * apk - s * aqk;
        a[3 * q + k] = s * apk + c * aqk;
      }
      for (int k = 0; k < 3; ++k) // v <- v J
      {
        const double vkp = v[3 * k + p], vkq = v[3 * k + q];
        v[3 * k + p] = c * vkp - s * vkq;
        v[3 * k + q] = s * vkp + c * vkq;
      }
    }
  }
  std::array<int, 3> order = {0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int i, int j) { return a[4 * i] < a[4 * j]; });
  Eigen3 e;
  for (int k = 0; k < 3; ++k)
  {
    e.values[k] = a[4 * order[k]];
    e.vectors[k] = {v[order[k]], v[3 + order[k]], v[6 + order[k]]};
  }
  return e;
}

std::vector<double> cholesky_solve(std::vector<double> A, std::vector<double> b)
{
  const std::size_t n = b.size();
  for (std::size_t j = 0; j < n; ++j) // A = L L^T, L in the lower triangle
  {
    double d = A[j * n + j];
    for (std::size_t k = 0; k < j; ++k)
      d -= A[j * n + k] * A[j * n + k];
    if (!(d > 0))
      throw std::runtime_error("cholesky_solve: the matrix is not positive definite");
    A[j * n + j] = std::sqrt(d);
    for (std::size_t i = j + 1; i < n; ++i)
    {
      double s = A[i * n + j];
      for (std::size_t k = 0; k < j; ++k)
        s -= A[i * n + k] * A[j * n + k];
      A[i * n + j] = s / A[j * n + j];
    }
  }
  for (std::size_t i = 0; i < n; ++i) // L y = b
  {
    for (std::size_t k = 0; k < i; ++k)
      b[i] -= A[i * n + k] * b[k];
    b[i] /= A[i * n + i];
  }
  for (std::size_t i = n; i-- > 0;) // L^T x = y
  {
    for (std::size_t k = i + 1; k < n; ++k)
      b[i] -= A[k * n + i] * b[k];
    b[i] /= A[i * n + i];
  }
  return b;
}

PlaneFit fit_plane(const std::vector<Vec3>& points, const std::vector<double>& weights)
{
  PlaneFit f{{0, 0, 0}, {}};
  double total = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    f.centroid = f.centroid + weights[i] * points[i];
    total += weights[i];
  }
  f.centroid = (1 / total) * f.centroid;
  std::array<double, 9> c{};
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Vec3 d = points[i] - f.centroid;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        c[3 * r + k] += weights[i] * d[r] * d[k] / total;
  }
  f.spread = symmetric_eigen(c);
  return f;
}
} // namespace breastsim::scan
