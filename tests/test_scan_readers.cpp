// SPDX-License-Identifier: LGPL-3.0-or-later
// The scan readers (src/scan/scan_readers.hpp): every format written by
// scan_writers is read back with its points and triangles; broken files
// (missing, unknown format, truncated binary, malformed lines, face indices
// out of range, an unread PLY format) are refused naming the file and the defect.
#include "errors.hpp"
#include "scan_fixtures.hpp"
#include "scan_readers.hpp"
#include "scan_writers.hpp"
#include <fstream>
#include <gtest/gtest.h>

using namespace scan_fixtures;
using breastsim::InputError;

namespace
{
void write_text(const std::filesystem::path& p, const std::string& text)
{
  std::ofstream(p, std::ios::binary) << text;
}

void expect_refused(const std::filesystem::path& p, Units u, const std::vector<std::string>& parts)
{
  try
  {
    read_scan(p, u);
    ADD_FAILURE() << p << " was accepted";
  }
  catch (const InputError& e)
  {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scan '" + p.string() + "'"), std::string::npos) << msg;
    for (const auto& part : parts)
      EXPECT_NE(msg.find(part), std::string::npos) << "expected \"" << part << "\" in: " << msg;
  }
}
} // namespace

TEST(ScanReaders, EveryFormatReadsBackItsPointsAndTriangles)
{
  ScratchDir dir;
  const ScanSurface cap = cap_scan(0.07, 0.06, 6, 12);
  const std::vector<std::pair<ScanFormat, std::string>> formats = {
      {ScanFormat::stl_binary, "a.stl"}, {ScanFormat::stl_ascii, "b.STL"}, {ScanFormat::ply_ascii, "c.ply"},
      {ScanFormat::ply_binary, "d.ply"}, {ScanFormat::obj, "e.obj"}};
  for (const auto& [format, name] : formats)
    for (Units u : {Units::mm, Units::m})
    {
      write_scan(cap, dir.path / name, format, u);
      const ScanSurface s = read_scan(dir.path / name, u);
      ASSERT_EQ(s.points.size(), cap.points.size()) << name; // STL corners merged back into shared points
      ASSERT_EQ(s.triangles.size(), cap.triangles.size()) << name;
      for (std::size_t t = 0; t < s.triangles.size(); ++t)
        for (int k = 0; k < 3; ++k)
          EXPECT_LT(norm(s.points[s.triangles[t][k]] - cap.points[cap.triangles[t][k]]), 1e-8) << name;
    }
}

TEST(ScanReaders, PointCloudsHaveNoTriangles)
{
  ScratchDir dir;
  const ScanSurface cap = cap_scan(0.07, 0.06, 6, 12);
  for (auto [format, name] : {std::pair{ScanFormat::ply_binary, "p.ply"}, std::pair{ScanFormat::obj, "p.obj"}})
  {
    write_scan(cap, dir.path / name, format, Units::mm, true);
    const ScanSurface s = read_scan(dir.path / name, Units::mm);
    EXPECT_TRUE(s.is_point_cloud());
    EXPECT_EQ(s.points.size(), cap.points.size());
  }
}

TEST(ScanReaders, RefusesMissingUnknownAndTruncatedFiles)
{
  ScratchDir dir;
  expect_refused(dir.path / "none.stl", Units::mm, {"no such file"});
  write_text(dir.path / "scan.xyz", "1 2 3\n");
  expect_refused(dir.path / "scan.xyz", Units::mm, {"unknown scan format '.xyz'", ".stl", ".ply", ".obj"});
  const ScanSurface cap = cap_scan(0.07, 0.06, 6, 12);
  write_scan(cap, dir.path / "full.stl", ScanFormat::stl_binary, Units::mm);
  std::filesystem::resize_file(dir.path / "full.stl", 84 + 50 * 10 + 7);
  expect_refused(dir.path / "full.stl", Units::mm, {"truncated binary STL", "triangle 10 is cut off"});
  write_text(dir.path / "short.stl", "abc");
  expect_refused(dir.path / "short.stl", Units::mm, {"truncated binary STL", "3 bytes"});
  write_scan(cap, dir.path / "full.ply", ScanFormat::ply_binary, Units::mm);
  std::filesystem::resize_file(dir.path / "full.ply", std::filesystem::file_size(dir.path / "full.ply") - 20);
  expect_refused(dir.path / "full.ply", Units::mm, {"truncated binary PLY", "face"});
}

TEST(ScanReaders, RefusesMalformedTextAndIndicesOutOfRange)
{
  ScratchDir dir;
  write_text(dir.path / "a.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 x 0\n");
  expect_refused(dir.path / "a.stl", Units::mm, {"line 5", "a vertex needs three numbers"});
  write_text(dir.path / "b.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expect_refused(dir.path / "b.obj", Units::mm, {"line 4", "names vertex 4", "3 vertices"});
  write_text(dir.path / "c.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
  expect_refused(dir.path / "c.obj", Units::mm, {"line 3", "at least 3 vertices"});
  write_text(dir.path / "d.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                 "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                 "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expect_refused(dir.path / "d.ply", Units::mm, {"names vertex 7", "3 vertices"});
  write_text(dir.path / "e.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\nend_header\n");
  expect_refused(dir.path / "e.ply", Units::mm, {"PLY format 'binary_big_endian' is not read"});
  write_text(dir.path / "f.ply", "solid\n");
  expect_refused(dir.path / "f.ply", Units::mm, {"not a PLY file"});
}

TEST(ScanReaders, UnitsAreStatedAsMmOrM)
{
  EXPECT_EQ(parse_units("mm", "--units"), Units::mm);
  EXPECT_EQ(parse_units("m", "--units"), Units::m);
  EXPECT_THROW(parse_units("cm", "--units"), InputError);
}
