// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Scans for the scan tests: a spherical cap's skin (base radius R, height H,
// base on the plane y = 0, apex at (0, H, 0)) triangulated on a polar
// grid with outward triangles, in metres; a scratch folder.
#include "scan_surface.hpp"
#include <cmath>
#include <filesystem>
#include <stdlib.h>

namespace scan_fixtures
{
using namespace breastsim::scan;

/// The cap's skin: the apex and `rings` rings of `sectors` points.
inline ScanSurface cap_scan(double R = 0.07, double H = 0.06, int rings = 24, int sectors = 72)
{
  ScanSurface s;
  s.where = "scan 'cap'";
  s.units = Units::m;
  const double Rs = (R * R + H * H) / (2 * H), yc = H - Rs;
  s.points.push_back({0, H, 0});
  for (int i = 1; i <= rings; ++i)
    for (int j = 0; j < sectors; ++j)
    {
      const double rho = R * i / rings, t = 2 * M_PI * j / sectors;
      const double x = rho * std::cos(t), z = rho * std::sin(t);
      s.points.push_back({x, std::max(0.0, yc + std::sqrt(Rs * Rs - x * x - z * z)), z});
    }
  auto idx = [&](int i, int j) -> std::int64_t { return i == 0 ? 0 : 1 + (i - 1) * sectors + (j % sectors); };
  // Outward (away from the chest, +y at the apex): (b - a) x (c - a) . e_y > 0 for a = apex, b = (1, j + 1), c = (1, j)
  for (int j = 0; j < sectors; ++j)
    s.triangles.push_back({0, idx(1, j + 1), idx(1, j)});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j)
    {
      s.triangles.push_back({idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)});
      s.triangles.push_back({idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)});
    }
  return s;
}

/// A scratch folder (mkdtemp), removed with its files at the end of the test.
struct ScratchDir
{
  std::filesystem::path path;
  ScratchDir()
  {
    std::string t = (std::filesystem::temp_directory_path() / "breastsim_scan_XXXXXX").string();
    path = ::mkdtemp(t.data());
  }
  ~ScratchDir() { std::filesystem::remove_all(path); }
};
} // namespace scan_fixtures
