// SPDX-License-Identifier: LGPL-3.0-or-later
// Reading a user's gmsh mesh (src/mesh/user_mesh.hpp): a good box is read
// with its tags, areas and volume; every bad file (written in a scratch
// folder through the gmsh API) is refused with a message that names the
// group, the cell or the node.
#include "errors.hpp"
#include "model.hpp"
#include "on_root.hpp"
#include "user_mesh.hpp"
#include <fstream>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <map>
#include <stdlib.h>

using namespace breastsim;
namespace fs = std::filesystem;

namespace
{
const meshes::UserMeshTags tags{1, 2, 3};

/// A scratch folder (mkdtemp), removed with its files at the end of the test.
struct ScratchDir
{
  fs::path path;
  ScratchDir()
  {
    std::string t = (fs::temp_directory_path() / "breastsim_user_mesh_XXXXXX").string();
    path = ::mkdtemp(t.data());
  }
  ~ScratchDir() { fs::remove_all(path); }
};

/// A mesh as plain arrays: node n has gmsh tag n + 1; elements by node tags.
struct RawMesh
{
  int order = 1;
  std::vector<double> x;
  std::vector<std::size_t> tets;
  std::vector<std::size_t> hexes;                           ///< extra 8-node cells in the volume
  std::vector<std::string> volume_groups{"tissue"};         ///< names of the volume's groups
  std::map<std::string, std::vector<std::size_t>> surfaces; ///< triangles by group name
};

// The box [0, 0.04] x [0, 0.03] x [-0.02, 0.02]: base y = 0, symmetry x = 0, skin the rest.
constexpr double box_x = 0.04, box_y = 0.03, box_z = 0.04;

/// The box meshed by gmsh (a few dozen tetrahedra of `order`).
RawMesh box_mesh(int order)
{
  meshes::GmshSession session;
  gmsh::model::occ::addBox(0, 0, -box_z / 2, box_x, box_y, box_z);
  gmsh::model::occ::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", 0.015);
  gmsh::model::mesh::generate(3);
  gmsh::model::mesh::setOrder(order);
  gmsh::model::mesh::renumberNodes();
  RawMesh m;
  m.order = order;
  // Fresh output vectors for every gmsh call: gmsh 4.8's getElementsByType
  // fills non-empty ones as if preallocated.
  std::vector<std::size_t> node_tags, tet_tags;
  std::vector<double> x, param;
  gmsh::model::mesh::getNodes(node_tags, x, param, -1, -1, false, false);
  m.x.resize(x.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i) // renumbered: tags 1, ..., n
    std::copy_n(x.begin() + 3 * i, 3, m.x.begin() + 3 * (node_tags[i] - 1));
  gmsh::model::mesh::getElementsByType(order == 1 ? 4 : 11, tet_tags, m.tets);
  gmsh::vectorpair faces;
  gmsh::model::getEntities(faces, 2);
  for (auto [d, t] : faces)
  {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(d, t, x0, y0, z0, x1, y1, z1);
    const std::string name = y1 < 1e-6 ? "base" : x1 < 1e-6 ? "symmetry" : "skin";
    std::vector<std::size_t> tri_tags, tri;
    gmsh::model::mesh::getElementsByType(order == 1 ? 2 : 9, tri_tags, tri, t);
    auto& s = m.surfaces[name];
    s.insert(s.end(), tri.begin(), tri.end());
  }
  return m;
}

/// Write `m` as a gmsh mesh file through the gmsh API.
fs::path write_msh(const RawMesh& m, const fs::path& file)
{
  meshes::GmshSession session;
  gmsh::model::addDiscreteEntity(3, 1);
  std::vector<std::size_t> node_tags(m.x.size() / 3);
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    node_tags[i] = i + 1;
  gmsh::model::mesh::addNodes(3, 1, node_tags, m.x);
  gmsh::model::mesh::addElementsByType(1, m.order == 1 ? 4 : 11, {}, m.tets);
  if (!m.hexes.empty())
    gmsh::model::mesh::addElementsByType(1, 5, {}, m.hexes);
  int group = 1;
  for (const auto& name : m.volume_groups)
  {
    gmsh::model::addPhysicalGroup(3, {1}, group);
    gmsh::model::setPhysicalName(3, group++, name);
  }
  int entity = 1;
  for (const auto& [name, tris] : m.surfaces)
  {
    gmsh::model::addDiscreteEntity(2, entity);
    gmsh::model::mesh::addElementsByType(entity, m.order == 1 ? 2 : 9, {}, tris);
    gmsh::model::addPhysicalGroup(2, {entity}, group);
    gmsh::model::setPhysicalName(2, group++, name);
    ++entity;
  }
  gmsh::write(file.string());
  return file;
}

/// read_user_mesh refuses the file with a message containing every part of `expected`.
void expect_refused(const fs::path& file, int order, const std::vector<std::string>& expected)
{
  try
  {
    meshes::read_user_mesh(file, order, tags);
    ADD_FAILURE() << "the mesh " << file << " was accepted";
  }
  catch (const InputError& e)
  {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("geometry.mesh_file = '" + file.string() + "'"), std::string::npos) << msg;
    for (const auto& part : expected)
      EXPECT_NE(msg.find(part), std::string::npos) << "expected \"" << part << "\" in: " << msg;
  }
}

std::size_t count(const std::vector<std::int32_t>& v, int value)
{
  return static_cast<std::size_t>(std::count(v.begin(), v.end(), value));
}
} // namespace

TEST(UserMesh, ReadsTheTetrahedraAndTheTaggedSurfacesOfBothOrders)
{
  ScratchDir dir;
  for (int order : {1, 2})
  {
    const RawMesh raw = box_mesh(order);
    const auto m = meshes::read_user_mesh(write_msh(raw, dir.path / "box.msh"), order, tags);
    const std::size_t npc = order == 1 ? 4 : 10, npf = order == 1 ? 3 : 6;
    EXPECT_EQ(m.order, order);
    EXPECT_EQ(m.num_cells(), raw.tets.size() / npc);
    EXPECT_EQ(m.num_nodes(), raw.x.size() / 3); // every node of the box is a node of a tetrahedron
    EXPECT_EQ(count(m.facet_tags, tags.base), raw.surfaces.at("base").size() / npf);
    EXPECT_EQ(count(m.facet_tags, tags.skin), raw.surfaces.at("skin").size() / npf);
    EXPECT_EQ(count(m.facet_tags, tags.symmetry), raw.surfaces.at("symmetry").size() / npf);
  }
}

TEST(UserMesh, DistributedMeshHasTheBoxAreasAndVolume)
{
  ScratchDir dir;
  fs::path file = dir.path / "box.msh";
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    write_msh(box_mesh(1), file);
  Model model(load_user_mesh(file, 1, MPI_COMM_WORLD));
  EXPECT_NEAR(model.area("base"), box_x * box_z, 1e-12);
  EXPECT_NEAR(model.area("symmetry"), box_y * box_z, 1e-12);
  EXPECT_NEAR(model.area("skin"), box_x * box_z + 2 * box_x * box_y + box_y * box_z, 1e-12);
  EXPECT_NEAR(model.volume(), box_x * box_y * box_z, 1e-15);
}

TEST(UserMesh, RefusesAMissingGroupOrAGroupOfTheWrongDimension)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  m.surfaces.erase("skin");
  expect_refused(write_msh(m, dir.path / "no_skin.msh"), 1,
                 {"no physical surface \"skin\"", "\"symmetry\" (dimension 2"});
  // Without "symmetry" the mesh is a full breast: the face x = 0 is then untagged.
  m = box_mesh(1);
  m.surfaces.erase("symmetry");
  expect_refused(write_msh(m, dir.path / "no_symmetry.msh"), 1, {"is in none of the surfaces"});
  m = box_mesh(1);
  m.volume_groups = {"body"};
  expect_refused(write_msh(m, dir.path / "no_tissue.msh"), 1, {"no physical volume \"tissue\"", "\"body\""});
  m = box_mesh(1);
  m.surfaces.erase("skin");
  m.volume_groups.push_back("skin");
  expect_refused(write_msh(m, dir.path / "skin_volume.msh"), 1,
                 {"physical group \"skin\" has dimension 3", "physical surface (dimension 2)"});
}

TEST(UserMesh, AFullBreastHasNoSymmetryFaceAndMayCrossXEqualsZero)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  auto& skin = m.surfaces.at("skin");
  skin.insert(skin.end(), m.surfaces.at("symmetry").begin(), m.surfaces.at("symmetry").end());
  m.surfaces.erase("symmetry");
  for (std::size_t n = 0; n < m.x.size() / 3; ++n)
    m.x[3 * n] -= box_x / 2; // the body across x = 0
  const auto full = meshes::read_user_mesh(write_msh(m, dir.path / "full.msh"), 1, tags);
  EXPECT_EQ(count(full.facet_tags, tags.symmetry), 0u);
  EXPECT_EQ(count(full.facet_tags, tags.skin), skin.size() / 3);
}

TEST(UserMesh, RefusesCellsThatAreNotTetrahedraOfTheCaseOrder)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  m.hexes = {1, 2, 3, 4, 5, 6, 7, 8};
  expect_refused(write_msh(m, dir.path / "hex.msh"), 1, {"physical volume \"tissue\"", "Hexahedron 8"});
  expect_refused(write_msh(box_mesh(1), dir.path / "p1.msh"), 2,
                 {"'Tetrahedron 4'", "geometry.order = 2", "'Tetrahedron 10'"});
}

TEST(UserMesh, RefusesAnInvertedTetrahedronNamingItAndItsVolume)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  std::swap(m.tets[4 * 3], m.tets[4 * 3 + 1]); // tetrahedron 3 turned inside out
  expect_refused(write_msh(m, dir.path / "inverted.msh"), 1,
                 {"tetrahedron 3 (gmsh element", "is inverted: signed volume -"});
}

TEST(UserMesh, RefusesAFoldedCurvedTetrahedron)
{
  ScratchDir dir;
  RawMesh m = box_mesh(2);
  // A mid-edge node of the skin pushed through the body to the far side.
  const std::size_t mid = m.surfaces.at("skin")[3] - 1;
  for (int i = 0; i < 3; ++i)
    m.x[3 * mid + i] = 2 * std::array<double, 3>{box_x / 2, box_y / 2, 0.0}[i] - m.x[3 * mid + i];
  expect_refused(write_msh(m, dir.path / "folded.msh"), 2, {"curved tetrahedron", "folds: det J = "});
}

TEST(UserMesh, RefusesASymmetryFaceOffThePlaneOrFacingTheWrongWay)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  for (std::size_t n = 0; n < m.x.size() / 3; ++n)
    m.x[3 * n] += 0.01; // the body moved off x = 0
  expect_refused(write_msh(m, dir.path / "shifted.msh"), 1,
                 {"surface \"symmetry\"", "is off the plane x = 0"});
  // Mirrored to x <= 0, each tetrahedron reordered to keep a positive volume:
  // the symmetry face now faces +x.
  m = box_mesh(1);
  for (std::size_t n = 0; n < m.x.size() / 3; ++n)
    m.x[3 * n] = -m.x[3 * n];
  for (std::size_t c = 0; c < m.tets.size() / 4; ++c)
    std::swap(m.tets[4 * c], m.tets[4 * c + 1]);
  expect_refused(write_msh(m, dir.path / "mirrored.msh"), 1,
                 {"surface \"symmetry\"", "outward normal (1, ", "must face -x"});
}

TEST(UserMesh, RefusesAnUntaggedOrDoublyTaggedBoundaryFace)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  auto& skin = m.surfaces.at("skin");
  const std::vector<std::size_t> first(skin.begin(), skin.begin() + 3);
  skin.erase(skin.begin(), skin.begin() + 3);
  expect_refused(write_msh(m, dir.path / "untagged.msh"), 1,
                 {"a boundary face of tetrahedron", "is in none of the surfaces"});
  auto& base = m.surfaces.at("base");
  base.insert(base.end(), first.begin(), first.end());
  skin.insert(skin.end(), first.begin(), first.end());
  expect_refused(write_msh(m, dir.path / "twice.msh"), 1,
                 {"surface \"base\"", "surface \"skin\"", "the same triangle"});
}

TEST(UserMesh, RefusesMillimetres)
{
  ScratchDir dir;
  RawMesh m = box_mesh(1);
  for (double& x : m.x)
    x *= 1000;
  expect_refused(write_msh(m, dir.path / "mm.msh"), 1, {"the mesh spans 40 m", "scale it by 0.001"});
}

TEST(UserMesh, RefusesAMissingFileAndFilesThatAreNoMeshNeverRunningAScript)
{
  ScratchDir dir;
  expect_refused(dir.path / "absent.msh", 1, {"no such file"});
  expect_refused(dir.path, 1, {"not a regular file"});
  const fs::path text = dir.path / "notes.msh";
  std::ofstream(text) << "hello world\n";
  expect_refused(text, 1, {"not a gmsh mesh", "$MeshFormat"});
  // A gmsh script under a mesh's name is refused before gmsh sees it.
  const fs::path script = dir.path / "script.msh", marker = dir.path / "ran";
  std::ofstream(script) << "System \"touch " << marker.string() << "\";\n";
  expect_refused(script, 1, {"not a gmsh mesh"});
  EXPECT_FALSE(fs::exists(marker));
  // A mesh file cut short: gmsh's own message.
  const fs::path cut = dir.path / "cut.msh";
  std::ofstream(cut) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\ngarbage\n";
  expect_refused(cut, 1, {"gmsh cannot read it"});
}

TEST(UserMesh, TheNippleMustBeASkinNode)
{
  ScratchDir dir;
  fs::path file = dir.path / "box.msh";
  if (rank_of(MPI_COMM_WORLD) == 0)
    write_msh(box_mesh(1), file);
  // The box's corner (0, box_y, box_z / 2) is a skin node; its centre line is not.
  EXPECT_NO_THROW(load_user_mesh(file, 1, MPI_COMM_WORLD, std::array<double, 3>{0, box_y, box_z / 2}));
  try
  {
    load_user_mesh(file, 1, MPI_COMM_WORLD, std::array<double, 3>{0, 0.05, 0});
    FAIL() << "a nipple off the mesh was accepted";
  }
  catch (const InputError& e)
  {
    const std::string m = e.what();
    EXPECT_NE(m.find("no skin node at the nipple (0, geometry.H = 0.05, geometry.nipple_z = 0)"),
              std::string::npos) << m;
    EXPECT_NE(m.find("the highest node on x = 0 is at y = 0.03"), std::string::npos) << m;
  }
}

TEST(UserMesh, EveryRankThrowsTheRootsInputError)
{
  ScratchDir dir;
  EXPECT_THROW(load_user_mesh(dir.path / "absent.msh", 1, MPI_COMM_WORLD), InputError);
}
