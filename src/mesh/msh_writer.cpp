// SPDX-License-Identifier: LGPL-3.0-or-later
#include "msh_writer.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>

namespace breastsim::meshes
{
void write_msh22(const TaggedMesh& m, const std::map<int, std::string>& facet_names,
                 const std::filesystem::path& file)
{
  std::ofstream f(file);
  f << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  // The volume's physical tag: one above every facet tag.
  int volume_tag = 1;
  for (const auto& [v, name] : facet_names)
    volume_tag = std::max(volume_tag, v + 1);
  f << "$PhysicalNames\n" << facet_names.size() + 1 << "\n";
  for (const auto& [v, name] : facet_names)
    f << "2 " << v << " \"" << name << "\"\n";
  f << "3 " << volume_tag << " \"tissue\"\n$EndPhysicalNames\n";
  f << "$Nodes\n" << m.num_nodes() << "\n";
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
    f << fmt::format("{} {:.17g} {:.17g} {:.17g}\n", n + 1, m.x[3 * n], m.x[3 * n + 1], m.x[3 * n + 2]);
  f << "$EndNodes\n";
  // Element types: 2/9 (3/6-node triangle), 4/11 (4/10-node tetrahedron).
  const std::size_t npf = m.nodes_per_facet(), npc = m.nodes_per_cell();
  const int facet_type = m.order == 1 ? 2 : 9, cell_type = m.order == 1 ? 4 : 11;
  f << "$Elements\n" << m.facet_tags.size() + m.num_cells() << "\n";
  std::size_t id = 1;
  auto element = [&](int type, int tag, const std::int64_t* nodes, std::size_t count)
  {
    f << id++ << " " << type << " 2 " << tag << " " << tag;
    for (std::size_t k = 0; k < count; ++k)
      f << " " << nodes[k] + 1;
    f << "\n";
  };
  for (std::size_t i = 0; i < m.facet_tags.size(); ++i)
    element(facet_type, m.facet_tags[i], &m.facets[i * npf], npf);
  for (std::size_t c = 0; c < m.num_cells(); ++c)
    element(cell_type, volume_tag, &m.cells[c * npc], npc);
  f << "$EndElements\n";
  if (!f.good())
    throw std::runtime_error("cannot write the mesh file " + file.string());
}
} // namespace breastsim::meshes
