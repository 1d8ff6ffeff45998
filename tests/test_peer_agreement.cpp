// SPDX-License-Identifier: LGPL-3.0-or-later
// Agreement with the peers' FEBio 4.11 / CalculiX 2.20 results
// (meshes/peers/README.md): the half cap R = 70 mm, H = 60 mm under gravity
// standing (mu = 2100 Pa, lambda = 0, rho = 970 kg/m^3, g = 9.81 m/s^2),
// base fixed, symmetry x = 0 sliding, no skin. The mesh is the peers' own:
// meshes/peers/halfcap_tagged.geo (halfcap.geo with its surfaces named)
// meshed by this gmsh library at the peers' lc, read back through the user
// mesh reader (src/mesh/user_mesh.hpp).
#include "breastsim_registry.hpp"
#include "fixtures.hpp"
#include "on_root.hpp"
#include "posture.hpp"
#include "errors.hpp"
#include "geometry_options.hpp"
#include "output_target.hpp"
#include "simulate.hpp"
#include "user_mesh.hpp"
#include <dolfinx/common/IndexMap.h>
#include <fstream>
#include <fmt/format.h>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <stdlib.h>

using namespace breastsim;
namespace fs = std::filesystem;

namespace
{
constexpr double cap_H = 0.06; // apex (0, H, 0)

fs::path peers_dir()
{
#ifdef BREASTSIM_SOURCE_DIR
  return fs::path(BREASTSIM_SOURCE_DIR) / "meshes" / "peers";
#else
  return fs::path(__FILE__).parent_path().parent_path() / "meshes" / "peers";
#endif
}

/// A scratch folder (mkdtemp), removed with its files at the end.
struct ScratchDir
{
  fs::path path;
  ScratchDir()
  {
    std::string t = (fs::temp_directory_path() / "breastsim_peer_XXXXXX").string();
    path = ::mkdtemp(t.data());
  }
  ~ScratchDir() { fs::remove_all(path); }
};

struct MeshCounts
{
  std::size_t tets = 0, nodes = 0;
};

/// The peers' command `gmsh -3 <geo> -setnumber lc <lc> [-order 2] -format
/// msh22 -o <out>` through the gmsh library; `out` empty: no file written.
MeshCounts mesh_geo(const std::string& geo, const std::string& lc, int order, const fs::path& out)
{
  const fs::path file = peers_dir() / geo;
  EXPECT_TRUE(fs::is_regular_file(file)) << file;
  std::vector<std::string> args{"gmsh", "-setnumber", "lc", lc};
  std::vector<char*> argv;
  for (auto& a : args)
    argv.push_back(a.data());
  gmsh::initialize(static_cast<int>(argv.size()), argv.data(), false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(file.string());
  gmsh::model::mesh::generate(3);
  if (order == 2)
    gmsh::model::mesh::setOrder(2);
  MeshCounts n;
  std::vector<std::size_t> tet_tags, tet_nodes, node_tags;
  gmsh::model::mesh::getElementsByType(order == 1 ? 4 : 11, tet_tags, tet_nodes);
  n.tets = tet_tags.size();
  std::vector<double> x, param;
  gmsh::model::mesh::getNodes(node_tags, x, param);
  n.nodes = node_tags.size();
  if (!out.empty())
  {
    gmsh::option::setNumber("Mesh.MshFileVersion", 2.2);
    gmsh::write(out.string());
  }
  gmsh::finalize();
  return n;
}

/// The peers' case: neo-Hookean tissue and gravity only, base fixed.
Config peer_case(int order)
{
  Config c;
  c.set("geometry.order", std::int64_t(order));
  c.set("tissue.mu", 2100.0);
  c.set("tissue.lambda", 0.0);
  c.set("tissue.rho", 970.0);
  c.set("gravity.g", 9.81);
  c.set("base.fixed", true);
  for (const auto& t : generated::terms())
    c.set("terms." + t.name, t.name == "tissue" || t.name == "gravity");
  c.validate();
  return c;
}

struct PeerResult
{
  std::int64_t tets = 0;
  double u_y = 0, u_z = 0; ///< apex displacement [m]
  int newton_iterations = 0;
};

/// Mesh halfcap_tagged.geo at `lc`, read it as a user mesh, solve standing.
PeerResult solve_peer_problem(const std::string& lc, int order)
{
  ScratchDir dir;
  const fs::path file = dir.path / "cap.msh";
  if (rank_of(MPI_COMM_WORLD) == 0)
    mesh_geo("halfcap_tagged.geo", lc, order, file);
  const Config c = peer_case(order);
  Model m(load_user_mesh(file, order, MPI_COMM_WORLD), Constraints{true, true});
  apply_parameters(c, m);
  NewtonOptions newton;
  newton.rtol = 1e-9; // |r| below 1e-9 of the gravity load
  const LoadPathReport path = fixtures::solve_gravity(m, gravity_vector(0.0, 9.81), newton);

  PeerResult r;
  r.tets = m.mesh().mesh->topology().index_map(3)->size_global();
  r.newton_iterations = path.newton_iterations;
  // The apex node (a vertex of the geometry, hence of the mesh): serial run.
  const std::vector<double> X = m.space()->tabulate_dof_coordinates(false);
  const auto u = m.displacement()->x()->array();
  std::size_t apex = 0;
  auto distance = [&](std::size_t n) { return std::hypot(X[3 * n], X[3 * n + 1] - cap_H, X[3 * n + 2]); };
  for (std::size_t n = 1; n < X.size() / 3; ++n)
    if (distance(n) < distance(apex))
      apex = n;
  EXPECT_LT(distance(apex), 1e-12);
  r.u_y = u[3 * apex + 1];
  r.u_z = u[3 * apex + 2];
  std::cout << fmt::format("peer problem lc {} P{}: {} tets, apex u_y = {:.8e}, u_z = {:.8e} m, {} Newton "
                           "iterations\n",
                           lc, order, r.tets, r.u_y, r.u_z, r.newton_iterations);
  return r;
}
} // namespace

TEST(PeerAgreement, GmshLibraryReproducesThePeersMeshesAndNamesChangeNothing)
{
  // meshes/peers/README.md: 4871 tets / 1205 nodes and 50369 / 9970 (gmsh 4.8 CLI).
  const MeshCounts coarse = mesh_geo("halfcap_tagged.geo", "0.00675", 1, {});
  EXPECT_EQ(coarse.tets, 4871u);
  EXPECT_EQ(coarse.nodes, 1205u);
  const MeshCounts fine = mesh_geo("halfcap_tagged.geo", "0.00303", 1, {});
  EXPECT_EQ(fine.tets, 50369u);
  EXPECT_EQ(fine.nodes, 9970u);
  const MeshCounts untagged = mesh_geo("halfcap.geo", "0.00303", 1, {});
  EXPECT_EQ(untagged.tets, fine.tets);
  EXPECT_EQ(untagged.nodes, fine.nodes);
}

// The peers' mesh exactly (counts above), so the results agree to the
// peers' printed digits: within 1e-10 m, one unit of their last digit
// (1.5e-8 of u_z, far inside 0.01 %; 1.1e-5 of u_y, a thousandth of u_z).
// Newton stops at |r| < 1e-9 of the load, which moves u by ~1e-12 m.
// Measured: u_z -6.71118032e-03, u_y -8.40427241e-06 (4871 tets);
// u_z -6.73512536e-03, u_y -9.21715372e-06 (50369); u_z -6.73732302e-03,
// u_y -9.82560225e-06 (201296).
constexpr double printed_digit = 1e-10;

TEST(PeerAgreement, ApexDisplacementP1On4871Tets)
{
  const PeerResult r = solve_peer_problem("0.00675", 1);
  EXPECT_EQ(r.tets, 4871);
  EXPECT_NEAR(r.u_z, -6.7111803e-03, printed_digit);
  EXPECT_NEAR(r.u_y, -8.4042724e-06, printed_digit);
}

TEST(PeerAgreement, ApexDisplacementP1On50369Tets)
{
  const PeerResult r = solve_peer_problem("0.00303", 1);
  EXPECT_EQ(r.tets, 50369);
  EXPECT_NEAR(r.u_z, -6.7351254e-03, printed_digit);
  EXPECT_NEAR(r.u_y, -9.2171538e-06, printed_digit);
}

TEST(PeerAgreement, LongApexDisplacementP1On201296Tets)
{
  const PeerResult r = solve_peer_problem("0.00187", 1);
  EXPECT_EQ(r.tets, 201296);
  EXPECT_NEAR(r.u_z, -6.7373230e-03, printed_digit);
  EXPECT_NEAR(r.u_y, -9.8256021e-06, printed_digit);
}

// P2 on curved 10-node meshes of the same family against the peers'
// Richardson value -6.7387e-03 within 0.05 %. Measured apex u_z [1e-3 m]
// (relative to -6.7387e-03): lc 0.018: -6.73065 (-1.2e-3); 0.0155: -6.73393
// (-7.1e-4); 0.014: -6.73487 (-5.7e-4); 0.0135 (841 tets): -6.73606
// (-3.9e-4, the coarsest within 0.05 %); 0.012: -6.73664; 0.0105: -6.73762;
// 0.009: -6.73841; 0.00675: -6.73914 (+6.5e-5); 0.00505: -6.73961;
// 0.00405: -6.73975; 0.00303 (50369 tets): -6.73985 (+1.7e-4). The P2
// sequence levels off near -6.7399e-03, 0.018 % beyond the P1 extrapolation.
TEST(PeerAgreement, ApexDisplacementP2WithinRichardsonValue)
{
  constexpr double richardson = -6.7387e-03;
  const PeerResult coarsest = solve_peer_problem("0.0135", 2);
  EXPECT_EQ(coarsest.tets, 841);
  EXPECT_NEAR(coarsest.u_z / richardson, 1.0, 5e-4);
  // On the peers' coarse mesh, P2 is 60 times closer than P1 (-4.1e-3).
  const PeerResult peers_coarse = solve_peer_problem("0.00675", 2);
  EXPECT_EQ(peers_coarse.tets, 4871);
  EXPECT_NEAR(peers_coarse.u_z / richardson, 1.0, 1e-4);
}

// The whole P2 table of docs/VERIFICATION.md: every level of the family
// within 0.05 % of the Richardson value from lc = 0.0135 on, and the finest
// two within 2e-5 of each other (the sequence levels off).
TEST(PeerAgreement, LongApexDisplacementP2Table)
{
  constexpr double richardson = -6.7387e-03;
  std::vector<double> u_z;
  for (const char* lc : {"0.018", "0.0135", "0.009", "0.00675", "0.00405", "0.00303"})
  {
    const PeerResult r = solve_peer_problem(lc, 2);
    if (std::string(lc) != "0.018")
      EXPECT_NEAR(r.u_z / richardson, 1.0, 5e-4) << "lc " << lc;
    u_z.push_back(r.u_z);
  }
  EXPECT_NEAR(u_z[5] / u_z[4], 1.0, 2e-5);
}

// The same problem as a user runs it: a case file whose geometry.mesh_file
// names the mesh relative to the case file, through the simulate job.
TEST(PeerAgreement, SimulateJobReadsTheCasesMeshFile)
{
  ScratchDir dir;
  if (rank_of(MPI_COMM_WORLD) == 0)
  {
    fs::create_directory(dir.path / "case");
    mesh_geo("halfcap_tagged.geo", "0.00675", 1, dir.path / "case" / "cap.msh");
    std::ofstream(dir.path / "case" / "peer.toml")
        << "[case]\nname = \"peer\"\n[geometry]\nmesh_file = \"cap.msh\"\n"
           "[tissue]\nmu = 2100.0\nlambda = 0.0\nrho = 970.0\n[base]\nfixed = true\n"
           "[terms]\nskin = false\nbase_springs = false\n[postures]\nnames = [\"standing\"]\n";
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const Config c = Config::from_file(dir.path / "case" / "peer.toml");
  EXPECT_EQ(c.text("geometry.mesh_file"), (dir.path / "case" / "cap.msh").string());
  const SimulationResult r
      = simulate(c, OutputTarget::claim((dir.path / "out").string(), {}, MPI_COMM_WORLD), MPI_COMM_WORLD);
  ASSERT_EQ(r.postures.size(), 1u);
  EXPECT_NEAR(r.postures[0].observables.nipple[2], -6.7111803e-03, 1e-9);
  EXPECT_NEAR(r.postures[0].observables.nipple[1], cap_H - 8.4042724e-06, 1e-9);
}

TEST(PeerAgreement, MeshFileKeysAreCheckedAtTheEdge)
{
  ScratchDir dir;
  Config c;
  auto message = [&](const std::string& key, const std::string& value)
  {
    Config d = c;
    try
    {
      d.set_text(key, value);
      d.validate();
    }
    catch (const InputError& e)
    {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(message("geometry.mesh_file", (dir.path / "absent.msh").string()).find("no such file"),
            std::string::npos);
  const fs::path file = dir.path / "cap.msh";
  std::ofstream(file) << "$MeshFormat\n";
  c.set_text("geometry.mesh_file", file.string());
  c.validate();
  EXPECT_NE(message("geometry.refinements", "1").find("geometry.refinements = 0"), std::string::npos);
  EXPECT_NE(message("geometry.rim_size_ratio", "0.5").find("geometry.rim_size_ratio = 1"),
            std::string::npos);
  try
  {
    HalfCapSpec::from(c).require_parametric_cap("surgery");
    FAIL() << "surgery on a user mesh was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("surgery needs the parametric cap"), std::string::npos);
  }
}
