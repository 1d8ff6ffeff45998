// SPDX-License-Identifier: LGPL-3.0-or-later
#include "nested_mesh.hpp"
#include "half_cap.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace breastsim
{
using meshes::TaggedMesh;

namespace
{
/// Edge midpoint nodes, created on first use (appended to m.x).
class Midpoints
{
public:
  explicit Midpoints(TaggedMesh& m) : m_(m) {}
  std::int64_t operator()(std::int64_t a, std::int64_t b)
  {
    const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
    auto [it, inserted] = index_.try_emplace(key, std::int64_t(m_.num_nodes()));
    if (inserted)
      for (int k = 0; k < 3; ++k)
        m_.x.push_back(0.5 * (m_.x[3 * a + k] + m_.x[3 * b + k]));
    return it->second;
  }

private:
  TaggedMesh& m_;
  std::unordered_map<std::uint64_t, std::int64_t> index_;
};

double dist2(const std::vector<double>& x, std::int64_t a, std::int64_t b)
{
  double s = 0;
  for (int k = 0; k < 3; ++k)
    s += (x[3 * a + k] - x[3 * b + k]) * (x[3 * a + k] - x[3 * b + k]);
  return s;
}
} // namespace

TaggedMesh refine_red(const TaggedMesh& m)
{
  if (m.order != 1)
    throw std::invalid_argument("refine_red: P1 meshes only");
  TaggedMesh r;
  r.order = 1;
  r.x = m.x;
  Midpoints mid(r);
  r.cells.reserve(8 * m.cells.size());
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    const std::int64_t* v = &m.cells[4 * c];
    const std::int64_t m01 = mid(v[0], v[1]), m02 = mid(v[0], v[2]), m03 = mid(v[0], v[3]),
                       m12 = mid(v[1], v[2]), m13 = mid(v[1], v[3]), m23 = mid(v[2], v[3]);
    // Four corner tetrahedra.
    for (const std::array<std::int64_t, 4>& t :
         {std::array<std::int64_t, 4>{v[0], m01, m02, m03}, {m01, v[1], m12, m13},
          {m02, m12, v[2], m23}, {m03, m13, m23, v[3]}})
      r.cells.insert(r.cells.end(), t.begin(), t.end());
    // Inner octahedron: opposite vertex pairs (m01, m23), (m02, m13), (m03, m12);
    // cut along the shortest of the three diagonals (a, b); the other four
    // vertices form the cycle p, q, p', q' around it: four tetrahedra.
    const std::array<std::array<std::int64_t, 2>, 3> pairs{{{m01, m23}, {m02, m13}, {m03, m12}}};
    int d = 0;
    for (int k = 1; k < 3; ++k)
      if (dist2(r.x, pairs[k][0], pairs[k][1]) < dist2(r.x, pairs[d][0], pairs[d][1]))
        d = k;
    const auto& P = pairs[(d + 1) % 3];
    const auto& Q = pairs[(d + 2) % 3];
    const std::array<std::int64_t, 4> ring{P[0], Q[0], P[1], Q[1]};
    for (int k = 0; k < 4; ++k)
    {
      const std::array<std::int64_t, 4> t{pairs[d][0], pairs[d][1], ring[k], ring[(k + 1) % 4]};
      r.cells.insert(r.cells.end(), t.begin(), t.end());
    }
  }
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
  {
    const std::int64_t* v = &m.facets[3 * f];
    const std::int64_t a = mid(v[0], v[1]), b = mid(v[1], v[2]), c = mid(v[2], v[0]);
    for (const std::array<std::int64_t, 3>& t : {std::array<std::int64_t, 3>{v[0], a, c},
                                                 {a, v[1], b}, {c, b, v[2]}, {a, b, c}})
      r.facets.insert(r.facets.end(), t.begin(), t.end());
    r.facet_tags.insert(r.facet_tags.end(), 4, m.facet_tags[f]);
  }
  return r;
}

TaggedMesh straight_p2(const TaggedMesh& m)
{
  if (m.order != 1)
    throw std::invalid_argument("straight_p2: P1 meshes only");
  TaggedMesh r;
  r.order = 2;
  r.x = m.x;
  Midpoints mid(r);
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    const std::int64_t* v = &m.cells[4 * c];
    r.cells.insert(r.cells.end(), v, v + 4);
    for (auto [a, b] : {std::pair{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}})
      r.cells.push_back(mid(v[a], v[b]));
  }
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
  {
    const std::int64_t* v = &m.facets[3 * f];
    r.facets.insert(r.facets.end(), v, v + 3);
    for (auto [a, b] : {std::pair{0, 1}, {1, 2}, {2, 0}})
      r.facets.push_back(mid(v[a], v[b]));
  }
  r.facet_tags = m.facet_tags;
  return r;
}

void snap_to_cap(TaggedMesh& m, double R, double H, int skin)
{
  const double Rs = meshes::sphere_radius(R, H), yc = H - Rs;
  const std::size_t npf = m.nodes_per_facet();
  std::vector<bool> on_skin(m.num_nodes(), false);
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
    if (m.facet_tags[f] == skin)
      for (std::size_t k = 0; k < npf; ++k)
        on_skin[m.facets[npf * f + k]] = true;
  for (std::size_t n = 0; n < on_skin.size(); ++n)
  {
    if (!on_skin[n])
      continue;
    double* x = &m.x[3 * n];
    if (std::abs(x[1]) < 1e-12 * R) // rim: x^2 + z^2 = R^2 in y = 0
    {
      const double s = R / std::hypot(x[0], x[2]);
      x[0] *= s, x[2] *= s;
    }
    else // sphere: |x - (0, yc, 0)| = Rs
    {
      const double s = Rs / std::sqrt(x[0] * x[0] + (x[1] - yc) * (x[1] - yc) + x[2] * x[2]);
      x[0] *= s, x[1] = yc + s * (x[1] - yc), x[2] *= s;
    }
  }
}
} // namespace breastsim
