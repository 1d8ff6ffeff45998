// SPDX-License-Identifier: LGPL-3.0-or-later
#include "tagged_mesh.hpp"
#include <cstdlib>
#include <gmsh.h>
#include <string>
#include <stdexcept>
#include <unordered_map>

namespace breastsim::meshes
{
namespace
{
/// gmsh's initialisation reads FLTK's preferences and creates
/// $HOME/.fltk/fltk.org/fltk.prefs when it is missing. A program must not
/// write into HOME uninvited: while gmsh initialises, HOME names a path that
/// cannot be created, so FLTK writes nothing; it is restored right after.
void initialize_gmsh_without_home()
{
  const char* home = std::getenv("HOME");
  const std::string saved = home ? home : "";
  setenv("HOME", "/dev/null/breastsim-no-home", 1);
  gmsh::initialize(0, nullptr, false);
  if (home)
    setenv("HOME", saved.c_str(), 1);
  else
    unsetenv("HOME");
}
} // namespace

GmshSession::GmshSession(bool verbose)
{
  initialize_gmsh_without_home();
  gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
  gmsh::option::setNumber("General.Verbosity", verbose ? 5 : 1);
  gmsh::model::add("breastsim");
}

GmshSession::~GmshSession() { gmsh::finalize(); }

TaggedMesh extract_tagged_mesh(int order, int refinements)
{
  gmsh::model::mesh::generate(3);
  for (int i = 0; i < refinements; ++i)
    gmsh::model::mesh::refine();
  if (order == 2)
    gmsh::model::mesh::setOrder(2);

  TaggedMesh m;
  m.order = order;
  const int tet_type = order == 1 ? 4 : 11;  // gmsh: 4-node / 10-node tetrahedron
  const int tri_type = order == 1 ? 2 : 9;   // gmsh: 3-node / 6-node triangle

  std::vector<std::size_t> node_tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1, false, false);
  std::unordered_map<std::size_t, std::int64_t> index;
  index.reserve(node_tags.size());

  // Keep only nodes used by tetrahedra, numbered in order of appearance.
  std::vector<std::size_t> etags, enodes;
  gmsh::model::mesh::getElementsByType(tet_type, etags, enodes);
  if (etags.empty())
    throw std::runtime_error("gmsh produced no tetrahedra");
  std::unordered_map<std::size_t, std::size_t> pos;
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    pos[node_tags[i]] = i;
  m.cells.reserve(enodes.size());
  for (std::size_t t : enodes)
  {
    auto [it, inserted] = index.try_emplace(t, static_cast<std::int64_t>(index.size()));
    if (inserted)
    {
      const std::size_t p = pos.at(t);
      m.x.insert(m.x.end(), coords.begin() + 3 * p, coords.begin() + 3 * p + 3);
    }
    m.cells.push_back(it->second);
  }

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 2);
  for (auto [dim, tag] : groups)
  {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    for (int e : entities)
    {
      std::vector<std::size_t> ftags, fnodes;
      gmsh::model::mesh::getElementsByType(tri_type, ftags, fnodes, e);
      for (std::size_t t : fnodes)
        m.facets.push_back(index.at(t));
      m.facet_tags.insert(m.facet_tags.end(), ftags.size(), tag);
    }
  }
  return m;
}
} // namespace breastsim::meshes
