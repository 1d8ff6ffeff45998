// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_model.hpp"
#include "scan_readers.hpp"
#include <algorithm>
#include <cmath>

namespace breastsim::scan
{
ScanModel fit_scan(const ScanSurface& skin, const ScanSurface* chest, const ScanModelOptions& o)
{
  check_scan(skin, o.limits);
  if (chest)
    check_scan(*chest, o.limits, true);
  ScanModel m;
  m.points = skin.points.size();
  m.triangles = skin.triangles.size();
  m.frame = breast_frame(skin, chest, o.frame, o.limits.max_hole);
  m.chest = measure_chest(m.frame, skin, chest);
  if (chest) // before the fit: a plane that misplaces the chest wall derails the fit
    check_chest_curvature(m.chest, o.limits.max_chest_rms, chest->where);
  const std::vector<std::size_t> used = fit_points(skin);
  std::vector<Vec3> pts;
  pts.reserve(used.size());
  for (std::size_t i : used)
    pts.push_back(m.frame.to_breast(skin.points[i]));
  m.points_used = used.size();
  m.fit = fit_radial(pts, o.degree, o.smoothing);
  const std::vector<double> r = radial_residuals(m.fit, pts);
  check_fit(skin, m.frame, m.fit, used, r, o.limits);
  if (!chest) // after the fit's checks: a noisy footprint is refused as noise, not as a curved chest
    check_chest_curvature(m.chest, o.limits.max_chest_rms, skin.where);
  double sum = 0;
  for (double v : r)
    sum += v * v;
  m.fit_rms = std::sqrt(sum / r.size());
  m.noise_rms = robust_rms(r);
  return m;
}

ScanModel build_scan_model(const std::filesystem::path& skin, const std::optional<std::filesystem::path>& chest,
                           const ScanModelOptions& o, int tag_base, int tag_skin, int tag_symmetry)
{
  const ScanSurface s = read_scan(skin, o.units);
  std::optional<ScanSurface> c;
  if (chest)
    c = read_scan(*chest, o.units);
  ScanModel m = fit_scan(s, c ? &*c : nullptr, o);
  // The nipple on the fitted skin, in the sagittal plane x = 0 of the frame.
  const Vec3 n = m.frame.to_breast(m.frame.nipple);
  Vec3 d{0, n[1], n[2]};
  d = (1 / norm(d)) * d;
  ScanMeshOptions mo = o.mesh;
  if (mo.mesh_size == 0) // automatic: h = 6 mm (V / 500 cm^3)^(1/3) in [4, 12] mm, about 10^4 tetrahedra
    mo.mesh_size = std::clamp(0.006 * std::cbrt(radial_volume(m.fit) / 500e-6), 0.004, 0.012);
  m.mesh_size = mo.mesh_size;
  m.half = mo.half;
  m.mesh = mesh_scan(m.fit, m.fit.radius(d) * d, mo, tag_base, tag_skin, tag_symmetry);
  return m;
}
} // namespace breastsim::scan
