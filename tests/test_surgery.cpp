// SPDX-License-Identifier: LGPL-3.0-or-later
// Surgery: incision geometry and remeshing against independent analytic
// computations, the suture term on a cap and a block, and the neutral-state
// reset.
#include "incision.hpp"
#include "errors.hpp"
#include "fixtures.hpp"
#include "output.hpp"
#include "reference_reset.hpp"
#include "surgery.hpp"
#include <gtest/gtest.h>
#include <gmsh.h>
#include <fstream>
#include <random>
#include <unistd.h>

using namespace breastsim;

namespace
{
Config surgery_case(double h = 0.008)
{
  Config c = fixtures::coarse_case(1, h);
  c.validate();
  return c;
}

/// Volume of the resected region (full breast) by midpoint quadrature of its
/// indicator over a fine grid of the analytic cap: independent of gmsh.
double analytic_resected_volume(const meshes::HalfCapSpec& cap, const meshes::IncisionGeometry& g)
{
  const double Rs = meshes::sphere_radius(cap.R, cap.H), yc = cap.H - Rs;
  const int n = 240;
  const double hx = cap.R / n, hy = cap.H / n, hz = 2 * cap.R / n;
  double v = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
      {
        const meshes::Point p = {(i + 0.5) * hx, (j + 0.5) * hy, -cap.R + (k + 0.5) * hz};
        const double r2 = p[0] * p[0] + (p[1] - yc) * (p[1] - yc) + p[2] * p[2];
        if (r2 < Rs * Rs && g.resected(p))
          v += hx * hy * hz;
      }
  return 2 * v;
}

double plane_distance(const meshes::Point& n, double c, const std::vector<double>& X, std::int32_t i)
{
  return n[0] * X[3 * i] + n[1] * X[3 * i + 1] + n[2] * X[3 * i + 2] - c;
}
} // namespace

TEST(Incision, ResectedVolumeMatchesTheAnalyticRegion)
{
  for (double a : {22.0, 35.0})
  {
    Config c = surgery_case();
    c.set("incision.a_deg", a);
    const auto cap = HalfCapSpec::from(c);
    const auto g = meshes::incision_geometry(cap, IncisionSpec::from(c));
    auto pre = fixtures::make_model(c);
    double cad = 0;
    meshes::TaggedMesh tm = meshes::mesh_incised_cap(cap, IncisionSpec::from(c), {1, 2, 3, 4, 5}, &cad);
    Model cut(to_dolfinx(MPI_COMM_WORLD, tm, 1));
    // The exact cap volume minus the remaining body's CAD volume, and the
    // meshes' volumes, against the grid quadrature of the analytic region.
    const double Rs = meshes::sphere_radius(cap.R, cap.H);
    const double cap_volume = M_PI * cap.H * cap.H * (3 * Rs - cap.H) / 3;
    const double expected = analytic_resected_volume(cap, g);
    EXPECT_NEAR((cap_volume - 2 * cad) / expected, 1.0, 0.01) << "a = " << a;
    EXPECT_NEAR(2 * (pre->volume() - cut.volume()) / expected, 1.0, 0.03) << "a = " << a;
    EXPECT_GT(expected, 0.05 * cap_volume);
  }
}

TEST(Incision, KeptAndResectedMeshesMakeUpTheCap)
{
  for (double a : {22.0, 35.0})
  {
    Config c = surgery_case();
    c.set("incision.a_deg", a);
    const auto cap = HalfCapSpec::from(c);
    const auto g = meshes::incision_geometry(cap, IncisionSpec::from(c));
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    meshes::TaggedMesh kept_tm, res_tm;
    kept_tm.order = res_tm.order = 1;
    if (rank == 0)
    {
      kept_tm = meshes::mesh_incised_cap(cap, IncisionSpec::from(c), {1, 2, 3, 4, 5});
      res_tm = meshes::mesh_resected_part(cap, IncisionSpec::from(c), {1, 2, 3, 4, 5});
    }
    Model kept(to_dolfinx(MPI_COMM_WORLD, kept_tm, 1)), resected(to_dolfinx(MPI_COMM_WORLD, res_tm, 1));
    // Volumes of the two meshes (half model) against the exact half cap
    // pi H^2 (3 Rs - H) / 6, and the resected mesh against the grid
    // quadrature of the analytic region.
    const double Rs = meshes::sphere_radius(cap.R, cap.H);
    const double half_cap = M_PI * cap.H * cap.H * (3 * Rs - cap.H) / 6;
    EXPECT_NEAR((kept.volume() + resected.volume()) / half_cap, 1.0, 0.01) << "a = " << a;
    std::cout << "a = " << a << " deg: (kept + resected) / cap = " << (kept.volume() + resected.volume()) / half_cap
              << ", resected mesh / analytic region = " << 2 * resected.volume() / analytic_resected_volume(cap, g)
              << "\n";
    EXPECT_NEAR(2 * resected.volume() / analytic_resected_volume(cap, g), 1.0, 0.03) << "a = " << a;
    // The resected part's cut faces are the kept body's suture faces.
    EXPECT_NEAR(resected.area("suture_abd") / kept.area("suture_abd"), 1.0, 0.01) << "a = " << a;
    EXPECT_NEAR(resected.area("suture_bcd") / kept.area("suture_bcd"), 1.0, 0.01) << "a = " << a;
    EXPECT_GT(resected.area("skin"), 0.0);
  }
}

TEST(Incision, ResectedPartMeshOfOrderTwoIsWritten)
{
  // P2: the curved skin of the resected part; volume within 1 % of the
  // analytic region and the XDMF (10-node tetrahedra, 6-node facet tags).
  Config c = surgery_case(0.012);
  c.set("geometry.order", std::int64_t(2));
  const auto cap = HalfCapSpec::from(c);
  const auto g = meshes::incision_geometry(cap, IncisionSpec::from(c));
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  meshes::TaggedMesh tm;
  tm.order = 2;
  if (rank == 0)
    tm = meshes::mesh_resected_part(cap, IncisionSpec::from(c), {1, 2, 3, 4, 5});
  auto dm = to_dolfinx(MPI_COMM_WORLD, tm, 2);
  Model resected(dm);
  EXPECT_NEAR(2 * resected.volume() / analytic_resected_volume(cap, g), 1.0, 0.01);
  const auto file = std::filesystem::temp_directory_path() / ("breastsim_resected_p2_" + std::to_string(::getpid()) + ".xdmf");
  write_mesh_xdmf(dm, file);
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0)
  {
    std::ifstream in(file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("Tetrahedron_10"), std::string::npos);
    EXPECT_NE(text.find("Triangle_6"), std::string::npos);
    std::filesystem::remove(file);
    std::filesystem::remove(std::filesystem::path(file).replace_extension(".h5"));
  }
}

TEST(Incision, SutureFacesLieOnTheirPlanesWithTheAnalyticAreas)
{
  Config c = surgery_case(0.004); // P1 faces: O(h^2) chord error along the skin
  const auto cap = HalfCapSpec::from(c);
  const auto g = meshes::incision_geometry(cap, IncisionSpec::from(c));
  meshes::TaggedMesh tm = meshes::mesh_incised_cap(cap, IncisionSpec::from(c), {1, 2, 3, 4, 5});
  Model m(to_dolfinx(MPI_COMM_WORLD, tm, 1));
  const auto X = m.space()->tabulate_dof_coordinates(false);
  for (auto n : m.boundary_nodes("suture_abd"))
    EXPECT_NEAR(plane_distance(g.n1, g.c1, X, n), 0.0, 1e-9);
  for (auto n : m.boundary_nodes("suture_bcd"))
    EXPECT_NEAR(plane_distance(g.n2, g.c2, X, n), 0.0, 1e-9);
  // Face areas by quadrature over each plane: points of the plane inside the
  // cap and not resected by the other cut (grid in plane coordinates).
  const double Rs = meshes::sphere_radius(cap.R, cap.H), yc = cap.H - Rs;
  auto face_area = [&](const meshes::Point& n, double cn, const meshes::Point& n_other, double c_other)
  {
    // Orthonormal in-plane basis (e1 along e_y, which both planes contain or nearly).
    meshes::Point e1 = {0, 1, 0};
    double p = e1[0] * n[0] + e1[1] * n[1] + e1[2] * n[2];
    for (int i = 0; i < 3; ++i)
      e1[i] -= p * n[i];
    double l = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (auto& v : e1)
      v /= l;
    meshes::Point e2 = {n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]};
    const int N = 800;
    const double L = 2 * Rs, dA = (2 * L / N) * (2 * L / N);
    double area = 0;
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j)
      {
        const double s1 = -L + (i + 0.5) * 2 * L / N, s2 = -L + (j + 0.5) * 2 * L / N;
        meshes::Point q;
        for (int k = 0; k < 3; ++k)
          q[k] = cn * n[k] + s1 * e1[k] + s2 * e2[k];
        const double r2 = q[0] * q[0] + (q[1] - yc) * (q[1] - yc) + q[2] * q[2];
        const bool kept_other = n_other[0] * q[0] + n_other[1] * q[1] + n_other[2] * q[2] >= c_other;
        if (r2 < Rs * Rs && q[0] >= 0 && q[1] >= 0 && kept_other)
          area += dA;
      }
    return area;
  };
  EXPECT_NEAR(m.area("suture_abd") / face_area(g.n1, g.c1, g.n2, g.c2), 1.0, 0.02);
  EXPECT_NEAR(m.area("suture_bcd") / face_area(g.n2, g.c2, g.n1, g.c1), 1.0, 0.02);
}

TEST(Incision, BadParametersAreRejectedByName)
{
  Config c = surgery_case();
  const auto cap = HalfCapSpec::from(c);
  auto expect_reject = [&](const std::string& key, double value)
  {
    auto inc = IncisionSpec::from(c);
    if (key == "incision.a_deg") inc.a_deg = value;
    if (key == "incision.s") inc.s = value;
    if (key == "incision.h") inc.h = value;
    if (key == "incision.d") inc.d = value;
    try
    {
      meshes::incision_geometry(cap, inc);
      ADD_FAILURE() << key << " = " << value << " was accepted";
    }
    catch (const InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_reject("incision.a_deg", 0.0);
  expect_reject("incision.a_deg", 89.0);  // B falls outside the base
  expect_reject("incision.s", 0.08);      // A is not on the skin (s >= R)
  expect_reject("incision.h", 0.07);      // D above the apex
  expect_reject("incision.d", 0.08);      // C outside the base
}

TEST(Sutures, ClosureReachesTheGapToleranceAndFacesSlide)
{
  Config c = surgery_case(0.012);
  meshes::TaggedMesh tm;
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    tm = meshes::mesh_incised_cap(HalfCapSpec::from(c), IncisionSpec::from(c), {1, 2, 3, 4, 5});
  Model m(to_dolfinx(MPI_COMM_WORLD, tm, 1));
  apply_parameters(c, m);
  const auto rep = close_sutures(m, c);
  EXPECT_LE(rep.max_gap, c.number("surgery.max_gap"));
  EXPECT_LE(max_suture_gap(m), 1e-4);
  EXPECT_GT(m.min_detF(), 0.0);
  // Sliding: the suture_abd nodes moved tangentially (in z) on the plane.
  const auto X = m.space()->tabulate_dof_coordinates(false);
  auto u = m.displacement()->x()->array();
  double slide = 0;
  for (auto n : m.boundary_nodes("suture_abd"))
    slide = std::max(slide, std::abs(u[3 * n + 2]));
  EXPECT_GT(slide, 1e-3);
  // Reset: the sutured shape is the new stress-free reference.
  const double V = m.volume();
  reset_reference(m);
  m.set_parameter("closure", {0.0}); // as surgery(): the faces hold their sewn positions
  EXPECT_EQ(fixtures::max_abs_u(m), 0.0);
  EXPECT_NEAR(m.volume() / V, 1.0, 1e-12); // the deformed volume is the new reference volume
  m.set_term("gravity", false);
  const double e0 = m.energy();
  EXPECT_LT(std::abs(e0), 1e-15); // round-off of the membrane at the identity
  auto r = fixtures::solve_gravity(m, {0.0, 0.0, 0.0});
  EXPECT_LT(fixtures::max_abs_u(m), 1e-12);
  EXPECT_LT(std::abs(m.energy()), 1e-15);
  EXPECT_EQ(r.failed_steps, 0);
}

TEST(Sutures, BlockFaceSewnToAPlaneEndsOnItAndSlides)
{
  // A 20 mm block x in [10, 30] mm: its face x = 10 mm is sewn to the plane
  // x = 0, its face x = 30 mm rests on a stiff spring bed.
  meshes::TaggedMesh tm;
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const double L = 0.02;
  if (rank == 0)
  {
    meshes::GmshSession session;
    const int box = gmsh::model::occ::addBox(0.01, 0, 0, L, L, L);
    gmsh::model::occ::synchronize();
    gmsh::vectorpair faces;
    gmsh::model::getBoundary({{3, box}}, faces, false, false, false);
    for (auto [d, t] : faces)
    {
      double x, y, z;
      gmsh::model::occ::getCenterOfMass(2, std::abs(t), x, y, z);
      if (std::abs(x - 0.01) < 1e-9)
        gmsh::model::addPhysicalGroup(2, {std::abs(t)}, 4); // suture_abd
      else if (std::abs(x - 0.03) < 1e-9)
        gmsh::model::addPhysicalGroup(2, {std::abs(t)}, 1); // base (springs)
    }
    gmsh::model::addPhysicalGroup(3, {box}, 1);
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.005);
    tm = meshes::extract_tagged_mesh(1, 0);
  }
  Model m(to_dolfinx(MPI_COMM_WORLD, tm, 1), Constraints{false, false});
  Config c = fixtures::coarse_case();
  c.set("surgery.max_gap", 1e-4 * L);
  apply_parameters(c, m);
  m.set_term("skin", false);
  m.set_parameter("c", {1e8});
  m.set_parameter("c_fold_ratio", {1.0});
  const auto rep = close_sutures(m, c);
  EXPECT_LE(rep.max_gap, 1e-4 * L);
  // Gravity along the plane (z): the sewn face slides down, still on the plane.
  NewtonSolver newton(m, NewtonOptions::from(c));
  const double f = set_gravity(m, {0.0, 0.0, -9.81});
  continuation(m, newton, "load", 0.0, 1.0, LoadStepOptions{}, "block", f);
  auto u = m.displacement()->x()->array();
  double slide = 0;
  for (auto n : m.boundary_nodes("suture_abd"))
    slide = std::max(slide, -u[3 * n + 2]);
  double global = 0;
  MPI_Allreduce(&slide, &global, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  EXPECT_GT(global, 1e-3 * L);            // it slides...
  EXPECT_LE(max_suture_gap(m), 1e-4 * L); // ...and stays on the plane
}
