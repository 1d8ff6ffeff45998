// SPDX-License-Identifier: LGPL-3.0-or-later
// PLY (Turk 1994): a text header (ply / format / element / property /
// end_header), then the elements in ASCII or binary little-endian. The
// vertex element's x, y, z are read; a face element's first list property
// (vertex_indices or vertex_index) gives polygons, split into fans. Other
// elements and properties are skipped.
#include "errors.hpp"
#include "scan_format_readers.hpp"
#include <cstring>
#include <map>
#include <sstream>

namespace breastsim::scan
{
namespace
{
struct Property
{
  std::string name, type;  ///< type of a scalar, or of the list's items
  std::string count_type;  ///< non-empty for a list
};

struct Element
{
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

struct Header
{
  bool binary = false;
  std::vector<Element> elements;
  std::size_t data_start = 0; ///< byte offset after end_header's line
};

std::size_t type_size(const std::string& t, const std::string& where)
{
  static const std::map<std::string, std::size_t> sizes = {
      {"char", 1},  {"uchar", 1}, {"int8", 1},    {"uint8", 1},  {"short", 2},   {"ushort", 2},
      {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},   {"int32", 4},   {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(t);
  if (it == sizes.end())
    throw InputError(fmt::format("{}: PLY property type '{}' is unknown", where, t));
  return it->second;
}

/// One little-endian binary value of type `t` at `p`, as a double.
double binary_value(const char* p, const std::string& t)
{
  auto get = [p](auto v) { std::memcpy(&v, p, sizeof v); return static_cast<double>(v); };
  if (t == "char" || t == "int8") return get(std::int8_t{});
  if (t == "uchar" || t == "uint8") return get(std::uint8_t{});
  if (t == "short" || t == "int16") return get(std::int16_t{});
  if (t == "ushort" || t == "uint16") return get(std::uint16_t{});
  if (t == "int" || t == "int32") return get(std::int32_t{});
  if (t == "uint" || t == "uint32") return get(std::uint32_t{});
  if (t == "float" || t == "float32") return get(float{});
  return get(double{});
}

Header parse_header(const std::string& b, const std::string& where)
{
  if (b.compare(0, 3, "ply") != 0)
    throw InputError(where + ": not a PLY file (its first line must be 'ply')");
  const std::size_t end = b.find("end_header");
  if (end == std::string::npos)
    throw InputError(where + ": the PLY header has no 'end_header' line");
  Header h;
  h.data_start = b.find('\n', end);
  h.data_start = h.data_start == std::string::npos ? b.size() : h.data_start + 1;
  std::istringstream in(b.substr(0, end));
  std::string line;
  bool format = false;
  while (std::getline(in, line))
  {
    std::istringstream w(line);
    std::string key;
    w >> key;
    if (key == "format")
    {
      std::string f;
      w >> f;
      if (f != "ascii" && f != "binary_little_endian")
        throw InputError(fmt::format("{}: PLY format '{}' is not read: allowed ascii, binary_little_endian", where, f));
      h.binary = f == "binary_little_endian";
      format = true;
    }
    else if (key == "element")
    {
      Element e;
      if (!(w >> e.name >> e.count))
        throw InputError(fmt::format("{}: malformed PLY header line '{}'", where, line));
      h.elements.push_back(e);
    }
    else if (key == "property")
    {
      if (h.elements.empty())
        throw InputError(fmt::format("{}: PLY property before any element: '{}'", where, line));
      Property p;
      w >> p.type;
      if (p.type == "list")
        w >> p.count_type >> p.type;
      w >> p.name;
      type_size(p.type, where);
      h.elements.back().properties.push_back(p);
    }
  }
  if (!format)
    throw InputError(where + ": the PLY header has no 'format' line");
  return h;
}

/// Reads values one at a time from the data part (ASCII words or binary).
class Values
{
public:
  Values(const std::string& b, const Header& h, const std::string& where)
      : _b(b), _binary(h.binary), _pos(h.data_start), _where(where), _text(b.substr(h.data_start))
  {
  }
  double next(const std::string& type, const std::string& what)
  {
    if (_binary)
    {
      const std::size_t n = type_size(type, _where);
      if (_pos + n > _b.size())
        throw InputError(fmt::format("{}: truncated binary PLY: the data ends in {} ({} bytes in the file)", _where,
                                     what, _b.size()));
      const double v = binary_value(_b.data() + _pos, type);
      _pos += n;
      return v;
    }
    std::string word;
    if (!(_text >> word))
      throw InputError(fmt::format("{}: the PLY data ends in {} (fewer values than the header announces)", _where,
                                   what));
    try
    {
      return std::stod(word);
    }
    catch (const std::exception&)
    {
      throw InputError(fmt::format("{}: '{}' in {} is not a number", _where, word, what));
    }
  }

private:
  const std::string& _b;
  bool _binary;
  std::size_t _pos;
  std::string _where;
  std::istringstream _text;
};

void read_element(const Element& e, Values& v, const std::string& where, ScanSurface& s)
{
  const bool vertex = e.name == "vertex", face = e.name == "face";
  for (std::size_t i = 0; i < e.count; ++i)
  {
    Vec3 p{0, 0, 0};
    std::vector<std::int64_t> poly;
    bool have_list = false;
    for (const Property& pr : e.properties)
    {
      const std::string what = fmt::format("{} {}", e.name, i);
      if (pr.count_type.empty())
      {
        const double x = v.next(pr.type, what);
        if (vertex && (pr.name == "x" || pr.name == "y" || pr.name == "z"))
          p[pr.name[0] - 'x'] = x;
        continue;
      }
      const double n = v.next(pr.count_type, what);
      for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k)
      {
        const double idx = v.next(pr.type, what);
        if (face && !have_list)
          poly.push_back(static_cast<std::int64_t>(idx));
      }
      have_list = true;
    }
    if (vertex)
      s.points.push_back(p);
    if (face && poly.size() < 3)
      throw InputError(fmt::format("{}: PLY face {} has {} vertices (at least 3)", where, i, poly.size()));
    for (std::size_t j = 1; face && j + 1 < poly.size(); ++j)
      s.triangles.push_back({poly[0], poly[j], poly[j + 1]});
  }
}
} // namespace

void read_ply(const std::string& b, const std::string& where, ScanSurface& s)
{
  const Header h = parse_header(b, where);
  bool has_xyz = false;
  for (const Element& e : h.elements)
    if (e.name == "vertex")
      for (const Property& p : e.properties)
        has_xyz |= p.name == "x";
  if (!has_xyz)
    throw InputError(where + ": the PLY file has no vertex element with properties x, y, z");
  Values v(b, h, where);
  for (const Element& e : h.elements)
    read_element(e, v, where, s);
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (std::int64_t i : s.triangles[t])
      if (i < 0 || i >= static_cast<std::int64_t>(s.points.size()))
        throw InputError(fmt::format("{}: PLY face (triangle {}) names vertex {}, but the file has {} vertices", where,
                                     t, i, s.points.size()));
}
} // namespace breastsim::scan
