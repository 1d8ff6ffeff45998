// SPDX-License-Identifier: LGPL-3.0-or-later
#include "user_mesh.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include "on_root.hpp"
#include "user_mesh_checks.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <gmsh.h>
#include <map>
#include <unordered_map>

namespace breastsim::meshes
{
namespace
{
namespace fs = std::filesystem;

/// gmsh's node tags and element tags of one kind of element, flat.
struct GmshElements
{
  std::vector<std::size_t> tags;
  std::vector<std::size_t> nodes;
};

/// A physical group: its dimension and tag.
struct Group
{
  int dim, tag;
};

std::string describe_type(int type)
{
  std::string name;
  int dim, order, nodes, primary;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
  return fmt::format("'{}' (gmsh type {})", name, type);
}

/// The file exists and is a gmsh mesh: its first line is $MeshFormat (a
/// gmsh script, whatever its name, is refused, never run).
void check_is_mesh_file(const fs::path& p, const std::string& where)
{
  std::error_code ec;
  if (!fs::exists(p, ec))
    throw InputError(where + ": no such file; give the path of a gmsh mesh (.msh)");
  if (!fs::is_regular_file(p, ec))
    throw InputError(where + ": not a regular file; give the path of a gmsh mesh (.msh)");
  std::ifstream in(p, std::ios::binary);
  std::string first;
  std::getline(in, first);
  if (!first.empty() && first.back() == '\r')
    first.pop_back();
  if (first != "$MeshFormat")
    throw InputError(where + ": not a gmsh mesh (its first line must be $MeshFormat: a .msh file of format "
                             "2.2 or 4.x, e.g. written by gmsh -3 file.geo -o file.msh; scripts are not run)");
}

void open_mesh(const fs::path& p, const std::string& where)
{
  try
  {
    gmsh::open(p.string());
  }
  catch (...) // gmsh throws its own types; its message is kept by the logger
  {
    std::string error;
    gmsh::logger::getLastError(error);
    throw InputError(where + ": gmsh cannot read it: " + (error.empty() ? "unknown error" : error));
  }
}

/// The physical group `name` of dimension `dim`, else an InputError naming
/// what the file holds.
Group find_group(const std::string& name, int dim, const std::string& where)
{
  const char* kind = dim == 3 ? "volume" : "surface";
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::string present;
  std::vector<int> dims_of_name;
  for (auto [d, t] : groups)
  {
    std::string n;
    gmsh::model::getPhysicalName(d, t, n);
    if (n == name && d == dim)
      return {d, t};
    if (n == name)
      dims_of_name.push_back(d);
    present += fmt::format("{}\"{}\" (dimension {}, tag {})", present.empty() ? "" : ", ", n, d, t);
  }
  if (!dims_of_name.empty())
    throw InputError(fmt::format("{}: physical group \"{}\" has dimension {}; it must be a physical {} "
                                 "(dimension {})",
                                 where, name, dims_of_name.front(), kind, dim));
  throw InputError(fmt::format("{}: no physical {} \"{}\" (dimension {}); the file has {}", where, kind, name,
                               dim, present.empty() ? "no physical groups" : "the groups " + present));
}

/// Is there a physical surface called `name`? (A full model has no "symmetry".)
bool has_surface_group(const std::string& name)
{
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  for (auto [d, t] : groups)
  {
    std::string n;
    gmsh::model::getPhysicalName(d, t, n);
    if (n == name)
      return true;
  }
  return false;
}

/// The elements of `group`, all of gmsh type `want` (else an InputError
/// naming the group, the element and what `order` allows).
GmshElements group_elements(const Group& group, const std::string& name, int want, int order,
                            const std::string& where)
{
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(group.dim, group.tag, entities);
  GmshElements out;
  for (int e : entities)
  {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, nodes;
    gmsh::model::mesh::getElements(types, tags, nodes, group.dim, e);
    for (std::size_t k = 0; k < types.size(); ++k)
    {
      if (types[k] != want && !tags[k].empty())
        throw InputError(fmt::format("{}: physical {} \"{}\": element {} is a {}; with geometry.order = {} "
                                     "the mesh must hold only {}",
                                     where, group.dim == 3 ? "volume" : "surface", name, tags[k].front(),
                                     describe_type(types[k]), order, describe_type(want)));
      out.tags.insert(out.tags.end(), tags[k].begin(), tags[k].end());
      out.nodes.insert(out.nodes.end(), nodes[k].begin(), nodes[k].end());
    }
  }
  if (out.tags.empty())
    throw InputError(fmt::format("{}: physical {} \"{}\" holds no elements (is the file meshed in 3D?)", where,
                                 group.dim == 3 ? "volume" : "surface", name));
  return out;
}

/// The nodes of the tetrahedra, numbered 0, 1, ... in order of first use;
/// their coordinates into m.x and the cells into m.cells.
std::unordered_map<std::size_t, std::int64_t> number_nodes(const GmshElements& tets, TaggedMesh& m)
{
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1, false, false);
  std::unordered_map<std::size_t, std::size_t> position;
  position.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    position[node_tags[i]] = i;
  std::unordered_map<std::size_t, std::int64_t> index;
  m.cells.reserve(tets.nodes.size());
  for (std::size_t t : tets.nodes)
  {
    auto [it, inserted] = index.try_emplace(t, static_cast<std::int64_t>(index.size()));
    if (inserted)
    {
      const std::size_t p = position.at(t);
      m.x.insert(m.x.end(), coords.begin() + 3 * p, coords.begin() + 3 * p + 3);
    }
    m.cells.push_back(it->second);
  }
  return index;
}

/// The triangles of surface `name` into m.facets with facet tag `value`.
void add_surface(const std::string& name, int value, int order,
                 const std::unordered_map<std::size_t, std::int64_t>& index, TaggedMesh& m,
                 UserMeshOrigin& origin)
{
  const Group g = find_group(name, 2, origin.where);
  const int tri_type = order == 1 ? 2 : 9; // gmsh: 3-node / 6-node triangle
  const GmshElements tris = group_elements(g, name, tri_type, order, origin.where);
  const std::size_t npf = m.nodes_per_facet();
  for (std::size_t f = 0; f < tris.tags.size(); ++f)
    for (std::size_t k = 0; k < npf; ++k)
    {
      const auto it = index.find(tris.nodes[f * npf + k]);
      if (it == index.end())
        throw InputError(fmt::format("{}: physical surface \"{}\": node {} of triangle (gmsh element {}) is "
                                     "no node of a tetrahedron of \"tissue\"",
                                     origin.where, name, tris.nodes[f * npf + k], tris.tags[f]));
      m.facets.push_back(it->second);
    }
  m.facet_tags.insert(m.facet_tags.end(), tris.tags.size(), value);
  origin.facet_elements.insert(origin.facet_elements.end(), tris.tags.begin(), tris.tags.end());
}
} // namespace

TaggedMesh read_user_mesh(const std::filesystem::path& path, int order, const UserMeshTags& tags)
{
  UserMeshOrigin origin{fmt::format("geometry.mesh_file = '{}'", path.string()), {}, {}, tags.base,
                        tags.skin, tags.symmetry, true};
  check_is_mesh_file(path, origin.where);
  GmshSession session;
  open_mesh(path, origin.where);

  TaggedMesh m;
  m.order = order;
  const Group tissue = find_group("tissue", 3, origin.where);
  const GmshElements tets = group_elements(tissue, "tissue", order == 1 ? 4 : 11, order, origin.where);
  origin.cell_elements = tets.tags;
  const auto index = number_nodes(tets, m);
  add_surface("base", tags.base, order, index, m, origin);
  add_surface("skin", tags.skin, order, index, m, origin);
  origin.half = has_surface_group("symmetry");
  if (origin.half)
    add_surface("symmetry", tags.symmetry, order, index, m, origin);
  check_user_mesh(m, origin);
  return m;
}
} // namespace breastsim::meshes

namespace breastsim
{
std::size_t nipple_node(const meshes::TaggedMesh& m, const std::filesystem::path& path,
                       const std::array<double, 3>& nipple)
{
  double extent = 0, top = -1;
  for (std::size_t i = 0; i < m.num_nodes(); ++i)
  {
    extent = std::max({extent, std::abs(m.x[3 * i]), std::abs(m.x[3 * i + 1]), std::abs(m.x[3 * i + 2])});
    if (std::abs(m.x[3 * i]) < 1e-9)
      top = std::max(top, m.x[3 * i + 1]);
  }
  const int skin = generated::tag("skin");
  const std::size_t npf = m.nodes_per_facet();
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
    for (std::size_t k = 0; k < npf && m.facet_tags[f] == skin; ++k)
    {
      const double* p = &m.x[3 * m.facets[f * npf + k]];
      if (std::hypot(p[0] - nipple[0], p[1] - nipple[1], p[2] - nipple[2]) <= 1e-6 * extent)
        return m.facets[f * npf + k];
    }
  throw InputError(fmt::format("geometry.mesh_file = '{}': no skin node at the nipple (0, geometry.H "
                               "= {:.6g}, geometry.nipple_z = {:.6g}), where the observables are read; "
                               "set geometry.H and geometry.nipple_z to the mesh's nipple node (the "
                               "highest node on x = 0 is at y = {:.6g})",
                               path.string(), nipple[1], nipple[2], top));
}

TaggedDolfinxMesh load_user_mesh(const std::filesystem::path& path, int order, MPI_Comm comm,
                                 const std::optional<std::array<double, 3>>& nipple)
{
  meshes::TaggedMesh m;
  m.order = order;
  on_root(comm,
          [&]
          {
            m = meshes::read_user_mesh(
                path, order, {generated::tag("base"), generated::tag("skin"), generated::tag("symmetry")});
            if (nipple)
              nipple_node(m, path, *nipple);
          });
  return to_dolfinx(comm, m, order);
}
} // namespace breastsim
