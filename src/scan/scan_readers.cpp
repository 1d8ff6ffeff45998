// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_readers.hpp"
#include "errors.hpp"
#include "scan_format_readers.hpp"
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace breastsim::scan
{
namespace
{
namespace fs = std::filesystem;

std::string read_bytes(const fs::path& path, const std::string& where)
{
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw InputError(where + ": no such file");
  if (!fs::is_regular_file(path, ec))
    throw InputError(where + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(where + ": cannot be opened for reading");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// Three numbers x y z from `in` (strtod: "nan" and "inf" are read, and refused later by the checks).
bool read_point(std::istringstream& in, Vec3& p)
{
  for (double& v : p)
  {
    std::string w;
    if (!(in >> w))
      return false;
    char* end = nullptr;
    v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0')
      return false;
  }
  return true;
}

/// The STL corners merged into points by equal coordinates.
void add_stl_triangle(const std::array<Vec3, 3>& corners, std::map<Vec3, std::int64_t>& index, ScanSurface& s)
{
  Triangle t;
  for (int k = 0; k < 3; ++k)
  {
    if (!std::isfinite(corners[k][0] + corners[k][1] + corners[k][2])) // NaN has no order: kept, not merged
    {
      t[k] = static_cast<std::int64_t>(s.points.size());
      s.points.push_back(corners[k]);
      continue;
    }
    auto [it, inserted] = index.try_emplace(corners[k], static_cast<std::int64_t>(s.points.size()));
    if (inserted)
      s.points.push_back(corners[k]);
    t[k] = it->second;
  }
  s.triangles.push_back(t);
}

/// Binary STL: 80-byte header, uint32 count, 50 bytes per triangle
/// (normal, three corners as float32, uint16 attribute).
void read_stl_binary(const std::string& b, const std::string& where, ScanSurface& s)
{
  std::uint32_t n = 0;
  std::memcpy(&n, b.data() + 80, 4);
  const std::size_t need = 84 + 50 * static_cast<std::size_t>(n);
  if (b.size() < need)
    throw InputError(fmt::format("{}: truncated binary STL: its header announces {} triangles ({} bytes), the file "
                                 "has {} bytes (triangle {} is cut off)",
                                 where, n, need, b.size(), (b.size() - 84) / 50));
  std::map<Vec3, std::int64_t> index;
  for (std::uint32_t t = 0; t < n; ++t)
  {
    std::array<Vec3, 3> c;
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
      {
        float v;
        std::memcpy(&v, b.data() + 84 + 50 * static_cast<std::size_t>(t) + 12 + 12 * k + 4 * i, 4);
        c[k][i] = v;
      }
    add_stl_triangle(c, index, s);
  }
}

/// ASCII STL: solid / facet normal / outer loop / 3 x vertex / endloop / endfacet.
void read_stl_ascii(const std::string& b, const std::string& where, ScanSurface& s)
{
  std::istringstream in(b);
  std::string line;
  std::map<Vec3, std::int64_t> index;
  std::array<Vec3, 3> c;
  int corner = 0, number = 0;
  while (std::getline(in, line))
  {
    ++number;
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word != "vertex")
      continue;
    Vec3& p = c[corner];
    if (!read_point(words, p))
      throw InputError(fmt::format("{}: line {}: a vertex needs three numbers: '{}'", where, number, line));
    if (++corner == 3)
    {
      add_stl_triangle(c, index, s);
      corner = 0;
    }
  }
  if (corner != 0)
    throw InputError(fmt::format("{}: the last facet has {} of its 3 vertices (the file is cut off?)", where,
                                 corner));
}
} // namespace

void read_stl(const std::string& b, const std::string& where, ScanSurface& s)
{
  // A binary STL's size is 84 + 50 n for the n in its header (its text header
  // may start with "solid" too); an ASCII STL starts with "solid".
  std::uint32_t n = 0;
  if (b.size() >= 84)
    std::memcpy(&n, b.data() + 80, 4);
  const bool ascii = b.compare(0, 5, "solid") == 0 && b.find("facet") != std::string::npos
                     && !(b.size() >= 84 && b.size() == 84 + 50 * static_cast<std::size_t>(n));
  if (ascii)
    return read_stl_ascii(b, where, s);
  if (b.size() < 84)
    throw InputError(fmt::format("{}: truncated binary STL: {} bytes, less than its 84-byte header (and not an "
                                 "ASCII STL starting with 'solid')",
                                 where, b.size()));
  read_stl_binary(b, where, s);
}

void read_obj(const std::string& b, const std::string& where, ScanSurface& s)
{
  std::istringstream in(b);
  std::string line;
  int number = 0;
  std::vector<std::vector<std::int64_t>> faces; // resolved after all v lines
  std::vector<int> face_lines;
  while (std::getline(in, line))
  {
    ++number;
    std::istringstream words(line);
    std::string key;
    if (!(words >> key))
      continue;
    if (key == "v")
    {
      Vec3 p;
      if (!read_point(words, p))
        throw InputError(fmt::format("{}: line {}: a vertex needs three numbers: '{}'", where, number, line));
      s.points.push_back(p);
    }
    else if (key == "f")
    {
      std::vector<std::int64_t> f;
      for (std::string w; words >> w;)
      {
        // "i", "i/t", "i//n", "i/t/n"; negative i counts back from the last vertex so far.
        std::int64_t i = 0;
        try
        {
          i = std::stoll(w.substr(0, w.find('/')));
        }
        catch (const std::exception&)
        {
          throw InputError(fmt::format("{}: line {}: '{}' is not a vertex index", where, number, w));
        }
        f.push_back(i < 0 ? static_cast<std::int64_t>(s.points.size()) + i : i - 1);
      }
      if (f.size() < 3)
        throw InputError(fmt::format("{}: line {}: a face needs at least 3 vertices: '{}'", where, number, line));
      faces.push_back(f);
      face_lines.push_back(number);
    }
  }
  for (std::size_t k = 0; k < faces.size(); ++k)
  {
    for (std::int64_t i : faces[k])
      if (i < 0 || i >= static_cast<std::int64_t>(s.points.size()))
        throw InputError(fmt::format("{}: line {}: face {} names vertex {}, but the file has {} vertices", where,
                                     face_lines[k], k, i + 1, s.points.size()));
    for (std::size_t j = 1; j + 1 < faces[k].size(); ++j) // a fan
      s.triangles.push_back({faces[k][0], faces[k][j], faces[k][j + 1]});
  }
}

Units parse_units(const std::string& text, const std::string& option)
{
  if (text == "mm")
    return Units::mm;
  if (text == "m")
    return Units::m;
  throw InputError(fmt::format("{} = '{}': the unit of the scan's coordinates must be stated: mm or m", option,
                               text));
}

ScanSurface read_scan(const std::filesystem::path& path, Units units)
{
  ScanSurface s;
  s.where = fmt::format("scan '{}'", path.string());
  s.units = units;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (ext != ".stl" && ext != ".ply" && ext != ".obj")
    throw InputError(fmt::format("{}: unknown scan format '{}': allowed .stl (ASCII or binary), .ply (ASCII or "
                                 "binary_little_endian), .obj",
                                 s.where, ext.empty() ? "(no extension)" : ext));
  const std::string bytes = read_bytes(path, s.where);
  if (ext == ".stl")
    read_stl(bytes, s.where, s);
  else if (ext == ".ply")
    read_ply(bytes, s.where, s);
  else
    read_obj(bytes, s.where, s);
  const double k = units == Units::mm ? 1e-3 : 1.0;
  for (Vec3& p : s.points)
    p = k * p;
  return s;
}
} // namespace breastsim::scan
