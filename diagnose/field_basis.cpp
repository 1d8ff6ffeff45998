// SPDX-License-Identifier: LGPL-3.0-or-later
#include "field_basis.hpp"
#include <algorithm>
#include <cmath>

namespace breastsim::diagnosis
{
bool in_half_cap(const Point& X, double R, double H)
{
  const double Rs = (R * R + H * H) / (2 * H), yc = H - Rs;
  const double d2 = X[0] * X[0] + (X[1] - yc) * (X[1] - yc) + X[2] * X[2];
  return X[0] >= 0 && X[1] >= 0 && d2 <= Rs * Rs;
}

namespace
{
std::vector<Point> lattice(double R, double H, double step)
{
  std::vector<Point> out;
  for (double x = step / 2; x < R; x += step)
    for (double y = step / 2; y < H; y += step)
      for (double z = -std::floor(R / step) * step; z <= R; z += step)
        if (in_half_cap({x, y, z}, R, H))
          out.push_back({x, y, z});
  return out;
}
} // namespace

FieldBasis lattice_basis(double R, double H)
{
  double step = std::max(R, H) / 4;
  std::vector<Point> c = lattice(R, H, step);
  while (c.size() > max_field_basis)
  {
    step *= 1.05;
    c = lattice(R, H, step);
  }
  return {c, 0.6 * step};
}

std::vector<double> basis_values(const FieldBasis& b, const Point& X)
{
  std::vector<double> phi;
  for (const Point& c : b.centres)
  {
    const double d2 = (X[0] - c[0]) * (X[0] - c[0]) + (X[1] - c[1]) * (X[1] - c[1])
                      + (X[2] - c[2]) * (X[2] - c[2]);
    phi.push_back(std::exp(-d2 / (2 * b.width * b.width))); // exp(-|X - c_k|^2 / 2 w^2)
  }
  return phi;
}

std::vector<double> basis_means(const FieldBasis& b, double R, double H)
{
  constexpr double step = 0.002;
  std::vector<double> m(b.centres.size(), 0.0);
  std::size_t n = 0;
  for (double x = step / 2; x < R; x += step)
    for (double y = step / 2; y < H; y += step)
      for (double z = -R + step / 2; z < R; z += step)
        if (in_half_cap({x, y, z}, R, H))
        {
          const auto phi = basis_values(b, {x, y, z});
          for (std::size_t k = 0; k < m.size(); ++k)
            m[k] += phi[k];
          ++n;
        }
  for (double& v : m)
    v /= static_cast<double>(std::max<std::size_t>(n, 1));
  return m;
}

double field_value(const FieldBasis& b, const std::vector<double>& a, const Point& X)
{
  const auto phi = basis_values(b, X);
  double s = 0;
  for (std::size_t k = 0; k < a.size() && k < phi.size(); ++k)
    s += a[k] * phi[k];
  return s;
}

Config with_field(Config c, const FieldBasis& b, const std::vector<double>& a)
{
  std::vector<double> amplitudes(max_field_basis, 0.0), centres(3 * max_field_basis, 0.0);
  for (std::size_t k = 0; k < b.centres.size() && k < max_field_basis; ++k)
  {
    amplitudes[k] = k < a.size() ? a[k] : 0.0;
    for (int i = 0; i < 3; ++i)
      centres[3 * k + i] = b.centres[k][i];
  }
  c.set("terms.tissue_field", true);
  c.set("tissue_field.amplitudes", amplitudes);
  c.set("tissue_field.centres", centres);
  c.set("tissue_field.width", b.width);
  return c;
}
} // namespace breastsim::diagnosis
