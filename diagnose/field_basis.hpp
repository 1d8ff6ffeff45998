// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The basis of a discovered stiffness field (forms/tissue_field.py):
//   s(X) = sum_k a_k exp(-|X - c_k|^2 / (2 w^2)),  stiffness exp(s(X)) x tissue,
// with centres c_k on a lattice inside the reference half cap.
#include "config.hpp"
#include "diagnosis.hpp"
#include <vector>

namespace breastsim::diagnosis
{
struct FieldBasis
{
  std::vector<Point> centres; ///< c_k [m]
  double width = 0;           ///< w [m]
};

/// Basis functions the compiled term holds (forms/tissue_field.py K).
constexpr std::size_t max_field_basis = 24;

/// True if X lies in the half cap of base radius R and height H (x >= 0,
/// y >= 0, inside the sphere of radius Rs = (R^2 + H^2) / 2H about (0, H - Rs, 0)).
bool in_half_cap(const Point& X, double R, double H);
/// Centres on a cubic lattice of spacing max(R, H) / 4 (offset half a
/// step from the base and the symmetry plane) inside the half cap, at most
/// max_field_basis of them (the spacing grows by 5 % until they fit);
/// width 0.6 x the spacing.
FieldBasis lattice_basis(double R, double H);
/// The mean of each basis function over the half cap (R, H), sampled on
/// a 2 mm lattice: s has volume mean sum_k m_k a_k.
std::vector<double> basis_means(const FieldBasis& b, double R, double H);
/// s(X) for amplitudes a (a.size() <= centres).
double field_value(const FieldBasis& b, const std::vector<double>& a, const Point& X);
/// The basis functions' values at X.
std::vector<double> basis_values(const FieldBasis& b, const Point& X);
/// `c` with the field term on, these centres and width, amplitudes a
/// (padded with zeros, unused centres at the origin).
Config with_field(Config c, const FieldBasis& b, const std::vector<double>& a);
} // namespace breastsim::diagnosis
