// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_writers.hpp"
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace breastsim::scan
{
namespace
{
void put(std::ofstream& f, const void* p, std::size_t n) { f.write(static_cast<const char*>(p), n); }

void write_stl(const ScanSurface& s, std::ofstream& f, bool binary, double k)
{
  if (!binary)
    f << "solid breastsim\n";
  else
  {
    const char header[80] = "breastsim scan";
    put(f, header, 80);
    const auto n = static_cast<std::uint32_t>(s.triangles.size());
    put(f, &n, 4);
  }
  for (const Triangle& t : s.triangles)
  {
    const Vec3 a = s.points[t[0]], b = s.points[t[1]], c = s.points[t[2]];
    Vec3 n = cross(b - a, c - a);
    n = norm(n) > 0 ? (1 / norm(n)) * n : n;
    if (!binary)
    {
      f << fmt::format("facet normal {:.9g} {:.9g} {:.9g}\n outer loop\n", n[0], n[1], n[2]);
      for (const Vec3& p : {a, b, c})
        f << fmt::format("  vertex {:.9g} {:.9g} {:.9g}\n", k * p[0], k * p[1], k * p[2]);
      f << " endloop\nendfacet\n";
      continue;
    }
    float v[12] = {float(n[0]), float(n[1]), float(n[2])};
    for (int c3 = 0; c3 < 3; ++c3)
      for (int i = 0; i < 3; ++i)
        v[3 + 3 * c3 + i] = static_cast<float>(k * s.points[t[c3]][i]);
    put(f, v, 48);
    const std::uint16_t attr = 0;
    put(f, &attr, 2);
  }
  if (!binary)
    f << "endsolid breastsim\n";
}

void write_ply(const ScanSurface& s, std::ofstream& f, bool binary, double k, bool points_only)
{
  const std::size_t faces = points_only ? 0 : s.triangles.size();
  f << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\ncomment breastsim scan\n"
    << "element vertex " << s.points.size() << "\nproperty float x\nproperty float y\nproperty float z\n";
  if (faces)
    f << "element face " << faces << "\nproperty list uchar int vertex_indices\n";
  f << "end_header\n";
  for (const Vec3& p : s.points)
  {
    const float v[3] = {float(k * p[0]), float(k * p[1]), float(k * p[2])};
    if (binary)
      put(f, v, 12);
    else
      f << fmt::format("{:.9g} {:.9g} {:.9g}\n", v[0], v[1], v[2]);
  }
  for (std::size_t t = 0; t < faces; ++t)
  {
    const std::int32_t idx[3] = {std::int32_t(s.triangles[t][0]), std::int32_t(s.triangles[t][1]),
                                 std::int32_t(s.triangles[t][2])};
    if (binary)
    {
      const std::uint8_t three = 3;
      put(f, &three, 1);
      put(f, idx, 12);
    }
    else
      f << "3 " << idx[0] << " " << idx[1] << " " << idx[2] << "\n";
  }
}

void write_obj(const ScanSurface& s, std::ofstream& f, double k, bool points_only)
{
  f << "# breastsim scan\n";
  for (const Vec3& p : s.points)
    f << fmt::format("v {:.9g} {:.9g} {:.9g}\n", k * p[0], k * p[1], k * p[2]);
  for (std::size_t t = 0; !points_only && t < s.triangles.size(); ++t)
    f << "f " << s.triangles[t][0] + 1 << " " << s.triangles[t][1] + 1 << " " << s.triangles[t][2] + 1 << "\n";
}
} // namespace

void write_scan(const ScanSurface& s, const std::filesystem::path& file, ScanFormat format, Units units,
                bool points_only)
{
  std::ofstream f(file, std::ios::binary);
  const double k = units == Units::mm ? 1e3 : 1.0;
  if (format == ScanFormat::stl_binary || format == ScanFormat::stl_ascii)
    write_stl(s, f, format == ScanFormat::stl_binary, k);
  else if (format == ScanFormat::obj)
    write_obj(s, f, k, points_only);
  else
    write_ply(s, f, format == ScanFormat::ply_binary, k, points_only);
  if (!f.good())
    throw std::runtime_error("cannot write the scan file " + file.string());
}
} // namespace breastsim::scan
