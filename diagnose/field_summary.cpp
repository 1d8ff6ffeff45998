// SPDX-License-Identifier: LGPL-3.0-or-later
#include "field_summary.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::diagnosis
{
namespace
{
/// Where a point of the half cap lies, in the clinic's words: the pole
/// (z, up standing), the depth (y, out of the chest), the distance from
/// the nipple axis (sqrt(x^2 + z^2)).
std::string clinical_place(const Point& c, double R, double H)
{
  std::vector<std::string> words;
  words.push_back(c[2] > 0.25 * R ? "in the upper pole" : c[2] < -0.25 * R ? "in the lower pole"
                                                                           : "at the nipple's level");
  words.push_back(c[1] < H / 3 ? "deep, near the chest wall"
                               : c[1] > 2 * H / 3 ? "near the apex, under the nipple" : "at mid-depth");
  const double rho = std::hypot(c[0], c[2]);
  if (c[2] < -0.6 * R && c[1] < H / 3)
    words.push_back("at the inframammary fold");
  else if (rho < 0.3 * R)
    words.push_back("on the nipple axis");
  else if (rho > 0.7 * R)
    words.push_back("at the periphery");
  std::string s;
  for (std::size_t i = 0; i < words.size(); ++i)
    s += (i ? ", " : "") + words[i];
  return s;
}

/// The candidates' physics a field of this place and sign resembles.
std::string resemblance(const FieldSummary& f, double R, double H)
{
  const Point& c = f.centroid;
  if (f.volume_share > 0.4)
    return f.factor > 1 ? "a gradual stiffening across much of the breast (no candidate has this form)"
                        : "a gradual softening across much of the breast (no candidate has this form)";
  if (f.factor < 1)
    return "a softer, fattier region (no candidate softens the tissue)";
  if (c[1] < 0.2 * H)
    return "a stiffer attachment to the chest (the base bed: base_springs)";
  if (std::hypot(c[0], c[2]) < 0.35 * R)
    return "a glandular core on the nipple axis (gland_core, gland_lobe)";
  if (c[2] > 0.25 * R && c[1] > H / 2)
    return "a stiffer upper-pole skin or ligaments (skin_upper_pole, suspensory_ligament)";
  return "a stiffer region of tissue (no candidate has this form)";
}

/// SE of s at X from the amplitudes' covariance: sqrt(phi^T C phi).
double se_at(const FieldBasis& b, const Matrix& cov, const Point& X)
{
  if (cov.empty())
    return 0;
  const auto phi = basis_values(b, X);
  double v = 0;
  for (std::size_t j = 0; j < cov.size() && j < phi.size(); ++j)
    for (std::size_t k = 0; k < cov.size() && k < phi.size(); ++k)
      v += phi[j] * cov[j][k] * phi[k];
  return std::sqrt(std::max(v, 0.0));
}
} // namespace

FieldSummary summarise_field(const FieldBasis& b, const std::vector<double>& a, const Matrix& cov_a,
                             double R, double H)
{
  constexpr double step = 0.002;
  std::vector<Point> pts;
  std::vector<double> s;
  for (double x = step / 2; x < R; x += step)
    for (double y = step / 2; y < H; y += step)
      for (double z = -R + step / 2; z < R; z += step)
        if (in_half_cap({x, y, z}, R, H))
        {
          pts.push_back({x, y, z});
          s.push_back(field_value(b, a, pts.back()));
        }
  FieldSummary f;
  if (pts.empty())
    return f;
  // Relative to the bulk of the tissue: s - median(s) (a uniform part of s
  // is a change of mu).
  std::vector<double> sorted = s;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  f.bulk_factor = std::exp(median);
  for (double& x : s)
    x -= median;
  const std::size_t peak = static_cast<std::size_t>(
      std::max_element(s.begin(), s.end(), [](double u, double v) { return std::abs(u) < std::abs(v); })
      - s.begin());
  const double sp = s[peak], se = se_at(b, cov_a, pts[peak]);
  f.peak = pts[peak];
  f.factor = std::exp(sp);
  f.factor_lo = std::exp(sp - 1.96 * se);
  f.factor_hi = std::exp(sp + 1.96 * se);
  Point lo = pts[peak], hi = pts[peak];
  std::size_t n = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (sp != 0 && s[i] * sp > 0 && std::abs(s[i]) >= 0.5 * std::abs(sp)) // the half-peak region
    {
      ++n;
      for (int k = 0; k < 3; ++k)
      {
        f.centroid[k] += pts[i][k];
        lo[k] = std::min(lo[k], pts[i][k]);
        hi[k] = std::max(hi[k], pts[i][k]);
      }
    }
  for (int k = 0; k < 3; ++k)
  {
    f.centroid[k] = n ? f.centroid[k] / static_cast<double>(n) : f.peak[k];
    f.extent_mm[k] = 1e3 * (hi[k] - lo[k] + step);
  }
  f.volume_share = static_cast<double>(n) / static_cast<double>(pts.size());
  f.where = clinical_place(f.centroid, R, H);
  f.resembles = resemblance(f, R, H);
  f.words = fmt::format(
      "the tissue is {:.2g} x as stiff as the rest (95 % {:.2g} - {:.2g}) {}, around (x, y, z) = ({:.0f}, {:.0f}, "
      "{:.0f}) mm, over about {:.0f} x {:.0f} x {:.0f} mm ({:.0f} % of the breast); it resembles {}",
      f.factor, f.factor_lo, f.factor_hi, f.where, 1e3 * f.centroid[0], 1e3 * f.centroid[1],
      1e3 * f.centroid[2], f.extent_mm[0], f.extent_mm[1], f.extent_mm[2], 100 * f.volume_share,
      f.resembles);
  return f;
}
} // namespace breastsim::diagnosis
