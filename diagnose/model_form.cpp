// SPDX-License-Identifier: LGPL-3.0-or-later
#include "model_form.hpp"
#include "linearised_refit.hpp"
#include "uncertainty.hpp"
#include <algorithm>
#include <array>
#include <cmath>

namespace breastsim::diagnosis
{
namespace
{
using Vec3 = std::array<double, 3>;

double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// C v for the 3 x 3 matrix C.
Vec3 mat_vec(const std::array<Vec3, 3>& C, const Vec3& v)
{
  return {dot3(C[0], v), dot3(C[1], v), dot3(C[2], v)};
}

/// Leading eigenvector of the symmetric C by power iteration, orthogonal to `away`
/// (deflation: v <- v - (v . away) away each step).
Vec3 leading_axis(const std::array<Vec3, 3>& C, const Vec3& away)
{
  Vec3 v{0.57735, 0.57735, 0.57735};
  for (int it = 0; it < 200; ++it)
  {
    Vec3 w = mat_vec(C, v);
    const double a = dot3(w, away);
    for (int k = 0; k < 3; ++k)
      w[k] -= a * away[k];
    const double n = std::sqrt(dot3(w, w));
    if (!(n > 0))
      return v;
    for (int k = 0; k < 3; ++k)
      v[k] = w[k] / n;
  }
  return v;
}

/// Covariance matrix of the points.
std::array<Vec3, 3> covariance(const std::vector<Point>& pts)
{
  Vec3 mean{0, 0, 0};
  for (const auto& p : pts)
    for (int k = 0; k < 3; ++k)
      mean[k] += p[k] / static_cast<double>(pts.size());
  std::array<Vec3, 3> C{};
  for (const auto& p : pts)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        C[a][b] += (p[a] - mean[a]) * (p[b] - mean[b]);
  return C;
}

/// `idx` split into b runs of (nearly) equal count, ordered by p . axis.
std::vector<std::vector<std::size_t>> slabs(std::vector<std::size_t> idx, const std::vector<Point>& pts,
                                            const Vec3& axis, int b)
{
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t i, std::size_t j)
                   { return dot3(pts[i], axis) < dot3(pts[j], axis); });
  std::vector<std::vector<std::size_t>> out(b);
  for (std::size_t k = 0; k < idx.size(); ++k)
    out[k * b / idx.size()].push_back(idx[k]);
  return out;
}
} // namespace

std::vector<std::vector<std::size_t>> principal_patches(const std::vector<Point>& points, int b)
{
  std::vector<std::size_t> all(points.size());
  for (std::size_t i = 0; i < all.size(); ++i)
    all[i] = i;
  if (b <= 1 || points.size() < static_cast<std::size_t>(2 * b * b))
    return {all};
  const auto C = covariance(points);
  const Vec3 first = leading_axis(C, {0, 0, 0});
  const Vec3 second = leading_axis(C, first);
  std::vector<std::vector<std::size_t>> patches;
  for (auto& slab : slabs(all, points, first, b))
    for (auto& patch : slabs(slab, points, second, b))
      patches.push_back(std::move(patch));
  return patches;
}

std::vector<double> group_jackknife_se(const FitState& s, const std::vector<std::vector<char>>& masks)
{
  const std::size_t n = s.values.size(), G = masks.size();
  std::vector<std::vector<double>> steps;
  for (const auto& held : masks)
    steps.push_back(step_without(s, held));
  std::vector<double> se(n, 0.0);
  for (std::size_t p = 0; p < n && G > 1; ++p)
  {
    double mean = 0, ss = 0;
    for (const auto& d : steps)
      mean += d[p] / static_cast<double>(G);
    for (const auto& d : steps)
      ss += (d[p] - mean) * (d[p] - mean);
    se[p] = std::sqrt(ss * static_cast<double>(G - 1) / static_cast<double>(G));
  }
  return se;
}

std::vector<double> posture_jackknife_se(const FitState& s, const Recording& rec)
{
  std::vector<std::vector<char>> masks;
  for (const auto& rows : rows_by_posture(s, rec))
    masks.push_back(mask_of(s, rows));
  return group_jackknife_se(s, masks);
}

std::vector<double> patch_jackknife_se(const FitState& s, const Recording& rec, int b)
{
  if (b <= 0)
    return std::vector<double>(s.values.size(), 0.0);
  std::vector<std::vector<char>> masks;
  std::size_t offset = 0; // first row of the posture's points
  for (std::size_t p = 0; p < s.distances.size() && p < rec.postures.size(); ++p)
  {
    for (const auto& patch : principal_patches(rec.postures[p].points, b))
    {
      std::vector<std::size_t> rows;
      for (std::size_t i : patch)
        rows.push_back(offset + i);
      masks.push_back(mask_of(s, rows));
    }
    offset += s.distances[p].size();
  }
  return group_jackknife_se(s, masks);
}

void estimate_model_form(const FitState& s, const Recording& rec, int b, Diagnosis& d)
{
  d.se_posture_jackknife = posture_jackknife_se(s, rec);
  d.se_patch_jackknife = patch_jackknife_se(s, rec, b);
  d.se_model_form.resize(d.se_posture_jackknife.size());
  for (std::size_t i = 0; i < d.se_model_form.size(); ++i)
    d.se_model_form[i] = std::max(d.se_posture_jackknife[i],
                                  i < d.se_patch_jackknife.size() ? d.se_patch_jackknife[i] : 0.0);
}

void widen_by_model_form(FitState& s, const std::vector<double>& se_model_form)
{
  auto& u = s.uncertainty;
  for (std::size_t i = 0; i < s.values.size() && i < u.se_log.size() && i < se_model_form.size(); ++i)
    widen_interval(u, i, s.values[i], se_model_form[i]);
}
} // namespace breastsim::diagnosis
