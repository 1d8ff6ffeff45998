// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_series.hpp"
#include "scan_readers.hpp"

namespace breastsim::scan
{
namespace
{
std::vector<Vec3> points_in_frame(const ScanSurface& s, const BreastFrame& f)
{
  std::vector<Vec3> pts;
  for (std::size_t i : fit_points(s))
    pts.push_back(f.to_breast(s.points[i]));
  return pts;
}
} // namespace

ScanSeries build_scan_series(const std::vector<std::filesystem::path>& skins, const std::filesystem::path& chest,
                             const ScanModelOptions& o, int tag_base, int tag_skin, int tag_symmetry,
                             double coarse_ratio)
{
  ScanSeries series;
  const ScanSurface c = read_scan(chest, o.units);
  for (std::size_t k = 0; k < skins.size(); ++k)
  {
    const ScanSurface s = read_scan(skins[k], o.units);
    if (k == 0)
    {
      series.first = build_scan_model(skins[0], chest, o, tag_base, tag_skin, tag_symmetry);
      series.first_points = points_in_frame(s, series.first.frame);
      if (coarse_ratio > 0)
      { // as build_scan_model: the nipple on the fitted skin in the sagittal plane x = 0
        const ScanModel& m = series.first;
        const Vec3 n = m.frame.to_breast(m.frame.nipple);
        Vec3 d{0, n[1], n[2]};
        d = (1 / norm(d)) * d;
        ScanMeshOptions mo = o.mesh;
        mo.mesh_size = coarse_ratio * m.mesh_size;
        series.coarse = mesh_scan(m.fit, m.fit.radius(d) * d, mo, tag_base, tag_skin, tag_symmetry);
      }
      continue;
    }
    const ScanModel m = fit_scan(s, &c, o); // the same checks as the first scan
    series.others.push_back({skins[k], points_in_frame(s, series.first.frame), m.noise_rms, m.fit_rms});
  }
  return series;
}
} // namespace breastsim::scan
