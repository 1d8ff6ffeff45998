// SPDX-License-Identifier: LGPL-3.0-or-later
#include "surface_export.hpp"
#include "breastsim_registry.hpp"
#include "output.hpp"
#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <stdexcept>

namespace breastsim
{
namespace
{
/// Barycentric lattice of a triangle cut into n x n: point (i, j) has
/// l1 = i/n, l2 = j/n, l0 = 1 - l1 - l2; index (i, j) -> i + j (n + 1) - j (j - 1) / 2.
int lattice_index(int i, int j, int n) { return i + j * (n + 1) - j * (j - 1) / 2; }

/// The sub-triangles (i, j), (i+1, j), (i, j+1) and (i+1, j), (i+1, j+1),
/// (i, j+1) of the n x n lattice, oriented like the triangle (0, 1, 2).
std::vector<std::array<int, 3>> lattice_triangles(int n)
{
  std::vector<std::array<int, 3>> t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i)
    {
      t.push_back({lattice_index(i, j, n), lattice_index(i + 1, j, n), lattice_index(i, j + 1, n)});
      if (i + j + 1 < n)
        t.push_back({lattice_index(i + 1, j, n), lattice_index(i + 1, j + 1, n),
                     lattice_index(i, j + 1, n)});
    }
  return t;
}

/// The six-node quadratic triangle (corners 0, 1, 2; edge nodes 01, 12, 20)
/// at barycentric (l0, l1, l2): sum of N_i x_i with N_i = l_i (2 l_i - 1) at
/// the corners and N_ij = 4 l_i l_j at the edge nodes.
std::array<double, 3> quadratic_point(const std::array<const double*, 6>& x, double l1, double l2)
{
  const double l0 = 1 - l1 - l2;
  const double N[6] = {l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1),
                       4 * l0 * l1,       4 * l1 * l2,       4 * l2 * l0};
  std::array<double, 3> p{0, 0, 0};
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c)
      p[c] += N[k] * x[k][c];
  return p;
}

/// Local vertices (0-3) of the reference tetrahedron's facet opposite
/// vertex `f`, ordered so that the normal points away from vertex f.
std::array<int, 3> outward_facet_vertices(const std::vector<double>& X, std::span<const std::int32_t> dofs,
                                          const dolfinx::fem::ElementDofLayout& layout, int f)
{
  std::array<int, 3> v;
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (i != f)
      v[k++] = i;
  auto p = [&](int lv, int c) { return X[3 * dofs[layout.entity_dofs(0, lv)[0]] + c]; };
  double e1[3], e2[3], d[3];
  for (int c = 0; c < 3; ++c)
  {
    e1[c] = p(v[1], c) - p(v[0], c);
    e2[c] = p(v[2], c) - p(v[0], c);
    d[c] = p(f, c) - p(v[0], c);
  }
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0)
    std::swap(v[1], v[2]);
  return v;
}

/// The dof of the reference tetrahedron's edge between local vertices a and
/// b (basix numbering: edges (2,3) (1,3) (1,2) (0,3) (0,2) (0,1)).
std::int32_t edge_dof(std::span<const std::int32_t> dofs, const dolfinx::fem::ElementDofLayout& layout, int a, int b)
{
  static const int edges[6][2] = {{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}};
  for (int e = 0; e < 6; ++e)
    if ((edges[e][0] == a && edges[e][1] == b) || (edges[e][0] == b && edges[e][1] == a))
      return dofs[layout.entity_dofs(1, e)[0]];
  throw std::logic_error("edge_dof: not an edge of the tetrahedron");
}

/// Local skin triangles of owned cells as (X, X + u) of the three corners
/// (u: local and ghost displacement dofs):
/// 18 doubles each, ordered so that the normal points out of the body. A P1
/// facet is one triangle; a P2 facet (six nodes, curved) is its quadratic
/// map sampled on the lattice of `kP2Subdivision`^2 flat sub-triangles, so
/// that the surface keeps the curvature of the geometry and the displacement
/// (flat corner facets of an h = 12 mm P2 mesh lie up to h^2 / 8R ~ 0.26 mm
/// inside a skin of radius 70 mm; the 4 x 4 lattice's up to 0.016 mm).
constexpr int kP2Subdivision = 4;

std::vector<double> local_triangles(const Model& model, std::span<const double> u)
{
  auto mesh = model.mesh().mesh;
  const auto& tags = *model.mesh().facets;
  auto& topology = mesh->topology_mutable();
  topology.create_connectivity(2, 3);
  topology.create_connectivity(3, 2);
  auto f_to_c = topology.connectivity(2, 3);
  auto c_to_f = topology.connectivity(3, 2);
  const std::int32_t owned_cells = topology.index_map(3)->size_local();

  auto V = model.space();
  const auto& layout = V->dofmap()->element_dof_layout();
  const bool quadratic = layout.num_entity_dofs(1) == 1;
  const int n = quadratic ? kP2Subdivision : 1;
  const auto sub = lattice_triangles(n);
  const auto X = V->tabulate_dof_coordinates(false);
  if (u.size() != X.size())
    throw std::logic_error("local_triangles: displacement and dof coordinates differ in size");
  std::vector<double> x(X.size());
  for (std::size_t i = 0; i < X.size(); ++i)
    x[i] = X[i] + u[i];
  const int skin = generated::tag("skin");

  std::vector<double> out;
  std::vector<std::array<double, 3>> ref, def;
  for (std::size_t i = 0; i < tags.values().size(); ++i)
  {
    if (tags.values()[i] != skin)
      continue;
    const std::int32_t facet = tags.indices()[i];
    const std::int32_t cell = f_to_c->links(facet)[0];
    if (cell >= owned_cells)
      continue; // another rank owns it
    const auto facets = c_to_f->links(cell);
    int local_facet = 0;
    while (facets[local_facet] != facet)
      ++local_facet;
    const auto dofs = V->dofmap()->cell_dofs(cell);
    const auto v = outward_facet_vertices(X, dofs, layout, local_facet);
    std::array<std::int32_t, 6> node;
    for (int k = 0; k < 3; ++k)
      node[k] = dofs[layout.entity_dofs(0, v[k])[0]];
    if (quadratic)
      for (int k = 0; k < 3; ++k)
        node[3 + k] = edge_dof(dofs, layout, v[k], v[(k + 1) % 3]);
    ref.clear();
    def.clear();
    if (!quadratic) // n = 1: the lattice is the corners themselves
      for (int k = 0; k < 3; ++k)
      {
        const std::int32_t c = node[k];
        ref.push_back({X[3 * c], X[3 * c + 1], X[3 * c + 2]});
        def.push_back({x[3 * c], x[3 * c + 1], x[3 * c + 2]});
      }
    else
    {
      std::array<const double*, 6> pr, pd;
      for (int k = 0; k < 6; ++k)
      {
        pr[k] = &X[3 * node[k]];
        pd[k] = &x[3 * node[k]];
      }
      for (int j = 0; j <= n; ++j)
        for (int i = 0; i + j <= n; ++i)
        {
          ref.push_back(quadratic_point(pr, double(i) / n, double(j) / n));
          def.push_back(quadratic_point(pd, double(i) / n, double(j) / n));
        }
    }
    for (const auto& t : sub)
    {
      for (int k = 0; k < 3; ++k)
        out.insert(out.end(), ref[t[k]].begin(), ref[t[k]].end());
      for (int k = 0; k < 3; ++k)
        out.insert(out.end(), def[t[k]].begin(), def[t[k]].end());
    }
  }
  return out;
}

std::vector<double> gather_to_root(const std::vector<double>& local, MPI_Comm comm)
{
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int n = static_cast<int>(local.size());
  std::vector<int> counts(size), displs(size, 0);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  for (int i = 1; i < size; ++i)
    displs[i] = displs[i - 1] + counts[i - 1];
  std::vector<double> all(rank == 0 ? displs.back() + counts.back() : 0);
  MPI_Gatherv(local.data(), n, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
              0, comm);
  return all;
}

double round_to(double v, double step) { return std::round(v / step) * step; }
} // namespace

bool is_half_model(const Model& model)
{
  const auto& tags = *model.mesh().facets;
  const int symmetry = generated::tag("symmetry");
  int local = static_cast<int>(
      std::count(tags.values().begin(), tags.values().end(), symmetry));
  int total = 0;
  MPI_Allreduce(&local, &total, 1, MPI_INT, MPI_SUM, model.mesh().mesh->comm());
  return total > 0;
}

SkinSurface gather_skin_surface(const Model& model)
{
  return gather_skin_surface(model, model.displacement()->x()->array());
}

SkinSurface gather_skin_surface(const Model& model, std::span<const double> u)
{
  MPI_Comm comm = model.mesh().mesh->comm();
  const auto all = gather_to_root(local_triangles(model, u), comm);
  SkinSurface s;
  s.half_model = is_half_model(model);
  // Merge corners shared by several triangles (and ranks) by reference
  // position, to a nanometre (ranks may differ in the last bits).
  std::map<std::array<std::int64_t, 3>, std::int32_t> index;
  for (std::size_t t = 0; t + 18 <= all.size(); t += 18)
  {
    std::array<std::int32_t, 3> tri;
    for (int k = 0; k < 3; ++k)
    {
      const double* ref = &all[t + 3 * k];
      const double* def = &all[t + 9 + 3 * k];
      const std::array<std::int64_t, 3> key = {std::llround(1e9 * ref[0]),
                                               std::llround(1e9 * ref[1]),
                                               std::llround(1e9 * ref[2])};
      auto [it, inserted] = index.try_emplace(key, static_cast<std::int32_t>(s.reference.size()));
      if (inserted)
      {
        s.reference.push_back({ref[0], ref[1], ref[2]});
        s.deformed.push_back({def[0], def[1], def[2]});
      }
      tri[k] = it->second;
    }
    s.triangles.push_back(tri);
  }
  return s;
}

nlohmann::json surface_json(const SkinSurface& s, const std::string& posture, double theta_deg)
{
  const double step = 1e-7; // 0.1 micrometre: plenty for pictures, keeps files small
  std::vector<double> ref, def, disp_mm;
  for (std::size_t i = 0; i < s.reference.size(); ++i)
  {
    double d2 = 0;
    for (int c = 0; c < 3; ++c)
    {
      ref.push_back(round_to(s.reference[i][c], step));
      def.push_back(round_to(s.deformed[i][c], step));
      d2 += std::pow(s.deformed[i][c] - s.reference[i][c], 2);
    }
    disp_mm.push_back(round_to(1e3 * std::sqrt(d2), 1e-4));
  }
  std::vector<std::int32_t> tris;
  for (const auto& t : s.triangles)
    tris.insert(tris.end(), t.begin(), t.end());
  nlohmann::json doc = {{"posture", posture},
                        {"theta_deg", theta_deg},
                        {"units", "m"},
                        {"mirror_x", s.half_model}};
  if (s.half_model)
    doc["half_model"] = "x >= 0; mirror x -> -x for the full breast";
  doc["vertices_ref"] = ref;
  doc["vertices"] = def;
  doc["triangles"] = tris;
  doc["fields"] = {{"displacement_mm", disp_mm}};
  return doc;
}

void write_surface(const Model& model, const std::string& posture, double theta_deg,
                   const std::filesystem::path& file)
{
  const auto s = gather_skin_surface(model);
  MPI_Comm comm = model.mesh().mesh->comm();
  int rank;
  MPI_Comm_rank(comm, &rank);
  write_text(file, rank == 0 ? surface_json(s, posture, theta_deg).dump() + "\n" : "", comm);
}
} // namespace breastsim
