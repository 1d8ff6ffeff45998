// SPDX-License-Identifier: LGPL-3.0-or-later
#include "skin_solid.hpp"
#include "scan_linalg.hpp"
#include <algorithm>
#include <cmath>
#include <gmsh.h>
#include <limits>
#include <set>
#include <stdexcept>

namespace breastsim::scan
{
namespace
{
constexpr int degree = 3; // cubic B-splines

/// The clamped uniform knot vector of n control points (n + degree + 1 knots).
std::vector<double> clamped_knots(int n)
{
  std::vector<double> k(degree, 0.0);
  for (int i = 0; i <= n - degree; ++i)
    k.push_back(static_cast<double>(i) / (n - degree));
  k.insert(k.end(), degree, 1.0);
  return k;
}

/// The n basis functions N_i(t) (Cox-de Boor), t in [0, 1].
std::vector<double> bspline_basis(const std::vector<double>& k, int n, double t)
{
  // Degree 0: the span [k_s, k_{s+1}) holding t (the last non-empty one at t = 1).
  std::vector<double> N(k.size() - 1, 0.0);
  int span = degree;
  while (span < n - 1 && t >= k[span + 1])
    ++span;
  N[span] = 1.0;
  for (int p = 1; p <= degree; ++p)
    for (std::size_t i = 0; i + p + 1 < k.size(); ++i)
    {
      const double a = k[i + p] > k[i] ? (t - k[i]) / (k[i + p] - k[i]) * N[i] : 0.0;
      const double b = k[i + p + 1] > k[i + 1] ? (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * N[i + 1] : 0.0;
      N[i] = a + b;
    }
  N.resize(n);
  return N;
}

/// Greville abscissae t_i = (k_{i+1} + ... + k_{i+degree}) / degree.
std::vector<double> greville(const std::vector<double>& k, int n)
{
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i)
    t[i] = (k[i + 1] + k[i + 2] + k[i + 3]) / degree;
  return t;
}

/// The disk's radius: a little beyond the chest circle (|(p, q)| = 1), so the
/// surface reaches y < 0 and the chest plane trims it.
constexpr double disk_radius = 1.06;

/// The skin point over square point (u, v): the elliptical square-to-disk map.
Vec3 skin_over_square(const RadialSurface& skin, double u, double v)
{
  const double p = u * std::sqrt(std::max(0.0, 1 - v * v / 2)), q = v * std::sqrt(std::max(0.0, 1 - u * u / 2));
  return skin.point(disk_radius * p, disk_radius * q);
}

/// Control points c (n x n, u fastest) with sum_ij N_i(t_a) N_j(t_b) c_ij = data(a, b):
/// the collocation solved along u, then along v (normal equations, Cholesky).
std::vector<Vec3> interpolating_poles(const std::vector<Vec3>& data, const std::vector<double>& k,
                                      const std::vector<double>& t, int n)
{
  std::vector<double> N(n * n), M(n * n, 0.0);
  for (int a = 0; a < n; ++a)
  {
    const auto row = bspline_basis(k, n, t[a]);
    std::copy(row.begin(), row.end(), N.begin() + a * n);
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < n; ++a)
        M[i * n + j] += N[a * n + i] * N[a * n + j];
  // Solve N x = b for one line of values b (stride `step` from `first`).
  auto solve_line = [&](std::vector<Vec3>& c, int first, int step)
  {
    for (int comp = 0; comp < 3; ++comp)
    {
      std::vector<double> rhs(n, 0.0);
      for (int i = 0; i < n; ++i)
        for (int a = 0; a < n; ++a)
          rhs[i] += N[a * n + i] * c[first + a * step][comp];
      const auto x = cholesky_solve(M, rhs);
      for (int i = 0; i < n; ++i)
        c[first + i * step][comp] = x[i];
    }
  };
  std::vector<Vec3> c = data;
  for (int b = 0; b < n; ++b)
    solve_line(c, b * n, 1); // along u
  for (int a = 0; a < n; ++a)
    solve_line(c, a, n); // along v
  return c;
}
} // namespace

int add_skin_solid(const RadialSurface& skin, int n)
{
  namespace occ = gmsh::model::occ;
  const std::vector<double> k = clamped_knots(n), t = greville(k, n);
  std::vector<Vec3> data(n * n);
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a)
      data[b * n + a] = skin_over_square(skin, 2 * t[a] - 1, 2 * t[b] - 1);
  std::vector<Vec3> poles = interpolating_poles(data, k, t, n);
  std::vector<int> points;
  double extent = 0;
  for (const Vec3& c : poles)
  {
    points.push_back(occ::addPoint(c[0], c[1], c[2]));
    extent = std::max(extent, norm(c));
  }
  std::vector<double> knots(k.begin() + degree, k.end() - degree);
  std::vector<int> mult(knots.size(), 1);
  mult.front() = mult.back() = degree + 1;
  const int surface = occ::addBSplineSurface(points, n, -1, degree, degree, {}, knots, knots, mult, mult);
  gmsh::vectorpair poles_tags;
  for (int p : points)
    poles_tags.push_back({0, p});
  occ::remove(poles_tags);
  // The skin reaches below the chest: it splits the box y in [0, L] into the
  // body under it (the smallest piece) and the rest.
  const double L = 3 * extent;
  const int box = occ::addBox(-L, 0, -L, 2 * L, L, 2 * L);
  gmsh::vectorpair pieces;
  std::vector<gmsh::vectorpair> map;
  occ::fragment({{3, box}}, {{2, surface}}, pieces, map);
  int body = -1;
  double smallest = std::numeric_limits<double>::infinity();
  for (auto [dim, tag] : pieces)
    if (double m; dim == 3 && (occ::getMass(3, tag, m), m < smallest))
      smallest = m, body = tag;
  gmsh::vectorpair rest;
  for (auto p : pieces)
    if (p != std::pair<int, int>{3, body})
      rest.push_back(p);
  occ::remove(rest, true);
  occ::synchronize();
  if (body < 0 || smallest > 0.5 * L * L * L)
    throw std::runtime_error("add_skin_solid: the fitted skin does not close a body with the chest plane");
  return body;
}

RadialSurface fit_mesh_skin(const meshes::TaggedMesh& m, int tag_skin, double* rms)
{
  std::set<std::int64_t> nodes;
  const std::size_t nf = m.nodes_per_facet();
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
    if (m.facet_tags[f] == tag_skin)
      nodes.insert(m.facets.begin() + f * nf, m.facets.begin() + (f + 1) * nf);
  if (nodes.size() < 66)
    throw std::runtime_error("fit_mesh_skin: fewer skin nodes than the fit's coefficients");
  std::vector<Vec3> points;
  for (auto n : nodes)
    points.push_back({m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]});
  RadialSurface fit = fit_radial(points, 10, 1e-7);
  if (rms)
  {
    double s = 0;
    for (double r : radial_residuals(fit, points))
      s += r * r;
    *rms = std::sqrt(s / points.size());
  }
  return fit;
}
} // namespace breastsim::scan
