#include "surface_export.hpp"
#include "breastsim_registry.hpp"
#include "output.hpp"
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace breastsim
{
namespace
{
/// Local skin triangles of owned cells as (X, x) of the three corners:
/// 18 doubles each, ordered so that the normal points out of the body.
std::vector<double> local_triangles(const Model& model)
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
  const auto X = V->tabulate_dof_coordinates(false);
  auto u = model.displacement()->x()->array();
  const int skin = generated::tag("skin");

  std::vector<double> out;
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
    // Reference tetrahedron: facet f is opposite vertex f.
    std::array<std::int32_t, 3> corner;
    int k = 0;
    for (int v = 0; v < 4; ++v)
      if (v != local_facet)
        corner[k++] = dofs[layout.entity_dofs(0, v)[0]];
    const std::int32_t opposite = dofs[layout.entity_dofs(0, local_facet)[0]];
    auto p = [&](std::int32_t n, int c) { return X[3 * n + c]; };
    double e1[3], e2[3], d[3];
    for (int c = 0; c < 3; ++c)
    {
      e1[c] = p(corner[1], c) - p(corner[0], c);
      e2[c] = p(corner[2], c) - p(corner[0], c);
      d[c] = p(opposite, c) - p(corner[0], c);
    }
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
    if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0)
      std::swap(corner[1], corner[2]);
    for (auto node : corner)
      for (int c = 0; c < 3; ++c)
        out.push_back(X[3 * node + c]);
    for (auto node : corner)
      for (int c = 0; c < 3; ++c)
        out.push_back(X[3 * node + c] + u[3 * node + c]);
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
  MPI_Comm comm = model.mesh().mesh->comm();
  const auto all = gather_to_root(local_triangles(model), comm);
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
