// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_topology.hpp"
#include "errors.hpp"
#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_map>

namespace breastsim::scan
{
namespace
{
std::string triangle_text(const ScanSurface& s, std::size_t t)
{
  const Triangle& v = s.triangles[t];
  return fmt::format("triangle {} (vertices {}, {}, {} at {}, {}, {})", t, v[0], v[1], v[2],
                     point_text(s, s.points[v[0]]), point_text(s, s.points[v[1]]), point_text(s, s.points[v[2]]));
}

/// Key of an undirected edge.
std::uint64_t edge_key(std::int64_t a, std::int64_t b)
{
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

/// Triangles of each undirected edge.
std::unordered_map<std::uint64_t, std::vector<std::size_t>> edge_triangles(const ScanSurface& s)
{
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> edges;
  edges.reserve(3 * s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      edges[edge_key(s.triangles[t][k], s.triangles[t][(k + 1) % 3])].push_back(t);
  return edges;
}

/// Does triangle t walk the edge from a to b?
bool walks(const Triangle& v, std::int64_t a, std::int64_t b)
{
  for (int k = 0; k < 3; ++k)
    if (v[k] == a && v[(k + 1) % 3] == b)
      return true;
  return false;
}

std::int64_t find_root(std::vector<std::int64_t>& parent, std::int64_t i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}
} // namespace

void check_degenerate_triangles(const ScanSurface& s)
{
  double extent = 0;
  for (const Vec3& p : s.points)
    extent = std::max({extent, std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    const Triangle& v = s.triangles[t];
    // area = |(b - a) x (c - a)| / 2; zero (to 1e-12 of the extent squared): no triangle
    const double area = 0.5 * norm(cross(s.points[v[1]] - s.points[v[0]], s.points[v[2]] - s.points[v[0]]));
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || area <= 1e-12 * extent * extent)
      throw InputError(fmt::format("{}: degenerate {}: it has no area (repeated or collinear corners)", s.where,
                                   triangle_text(s, t)));
  }
}

void check_duplicated_triangles(const ScanSurface& s)
{
  std::map<std::array<std::int64_t, 3>, std::size_t> seen;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    std::array<std::int64_t, 3> key = s.triangles[t];
    std::sort(key.begin(), key.end());
    const auto [it, inserted] = seen.emplace(key, t);
    if (!inserted)
      throw InputError(fmt::format("{}: duplicated triangle: {} repeats triangle {} (same three vertices)", s.where,
                                   triangle_text(s, t), it->second));
  }
}

void check_edges(const ScanSurface& s)
{
  const auto edges = edge_triangles(s);
  for (const auto& [key, tris] : edges)
  {
    const std::int64_t a = static_cast<std::int64_t>(key >> 32), b = static_cast<std::int64_t>(key & 0xffffffffu);
    if (tris.size() > 2)
      throw InputError(fmt::format("{}: non-manifold edge between vertices {} {} and {} {}: shared by {} triangles "
                                   "({}, {}, {}...); a skin surface has at most two triangles on an edge",
                                   s.where, a, point_text(s, s.points[a]), b, point_text(s, s.points[b]),
                                   tris.size(), tris[0], tris[1], tris[2]));
    if (tris.size() == 2 && walks(s.triangles[tris[0]], a, b) == walks(s.triangles[tris[1]], a, b))
      throw InputError(fmt::format("{}: inconsistent orientation: triangles {} and {} walk their shared edge (vertices "
                                   "{} {} and {} {}) the same way; the triangles must be oriented consistently",
                                   s.where, tris[0], tris[1], a, point_text(s, s.points[a]), b,
                                   point_text(s, s.points[b])));
  }
}

void check_connected(const ScanSurface& s)
{
  std::vector<std::int64_t> parent(s.points.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Triangle& v : s.triangles)
    for (int k = 1; k < 3; ++k)
      parent[find_root(parent, v[k])] = find_root(parent, v[0]);
  std::map<std::int64_t, std::size_t> size; // root -> triangles
  for (const Triangle& v : s.triangles)
    ++size[find_root(parent, v[0])];
  if (size.size() <= 1)
    return;
  auto largest = std::max_element(size.begin(), size.end(), [](auto& a, auto& b) { return a.second < b.second; });
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    if (const std::int64_t r = find_root(parent, s.triangles[t][0]); r != largest->first)
      throw InputError(fmt::format("{}: the scan has {} disconnected pieces; the largest has {} triangles, another "
                                   "({} triangles) starts at triangle {} at {}: remove the stray pieces",
                                   s.where, size.size(), largest->second, size[r], t,
                                   point_text(s, s.points[s.triangles[t][0]])));
}

std::vector<std::vector<std::int64_t>> boundary_loops(const ScanSurface& s)
{
  std::unordered_map<std::int64_t, std::vector<std::int64_t>> next; // boundary edges a -> b, as walked
  for (const auto& [key, tris] : edge_triangles(s))
    if (tris.size() == 1)
    {
      const std::int64_t a = static_cast<std::int64_t>(key >> 32), b = static_cast<std::int64_t>(key & 0xffffffffu);
      walks(s.triangles[tris[0]], a, b) ? next[a].push_back(b) : next[b].push_back(a);
    }
  for (const auto& [a, to] : next)
    if (to.size() > 1)
      throw InputError(fmt::format("{}: the open boundary touches itself at vertex {} {} (two boundary loops share "
                                   "it): holes must not touch each other or the footprint",
                                   s.where, a, point_text(s, s.points[a])));
  std::vector<std::vector<std::int64_t>> loops;
  std::vector<std::int64_t> starts;
  for (const auto& [a, to] : next)
    starts.push_back(a);
  std::sort(starts.begin(), starts.end()); // deterministic order
  std::unordered_map<std::int64_t, bool> used;
  for (std::int64_t start : starts)
  {
    if (used[start])
      continue;
    std::vector<std::int64_t> loop;
    for (std::int64_t v = start; !used[v];)
    {
      used[v] = true;
      loop.push_back(v);
      const auto it = next.find(v);
      if (it == next.end())
        throw InputError(fmt::format("{}: the open boundary ends at vertex {} {} without closing", s.where, v,
                                     point_text(s, s.points[v])));
      v = it->second.front();
    }
    loops.push_back(loop);
  }
  return loops;
}

double loop_length(const ScanSurface& s, const std::vector<std::int64_t>& loop)
{
  double l = 0;
  for (std::size_t k = 0; k < loop.size(); ++k)
    l += norm(s.points[loop[(k + 1) % loop.size()]] - s.points[loop[k]]);
  return l;
}
} // namespace breastsim::scan
