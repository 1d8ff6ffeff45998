// SPDX-License-Identifier: LGPL-3.0-or-later
// The parametric half cap: tags, areas and volume against closed forms,
// the nipple vertex, and mesh quality.
#include "half_cap.hpp"
#include "fixtures.hpp"
#include "mesh_quality.hpp"
#include <gtest/gtest.h>

using namespace breastsim;

namespace
{
struct CapCase
{
  double R, H;
  int order;
};
class HalfCap : public ::testing::TestWithParam<CapCase>
{
};
} // namespace

TEST_P(HalfCap, TagsAreasAndVolumeMatchTheSphericalCap)
{
  const auto [R, H, order] = GetParam();
  Config c = fixtures::coarse_case(order, std::min(R, H) / 5);
  c.set("geometry.R", R);
  c.set("geometry.H", H);
  c.validate();
  auto m = fixtures::make_model(c);
  const double Rs = meshes::sphere_radius(R, H);
  // Half of: base disc pi R^2, cap surface 2 pi Rs H, cap volume pi H^2 (3 Rs - H) / 3.
  const double base = M_PI * R * R / 2, skin = M_PI * Rs * H;
  const double volume = M_PI * H * H * (3 * Rs - H) / 6;
  // Symmetry face: the circular segment of the sphere's great circle cut at y = 0.
  const double phi = 2 * std::acos((Rs - H) / Rs);
  const double symmetry = Rs * Rs / 2 * (phi - std::sin(phi));
  // P1 facets are chords (O(h^2) error), P2 facets are curved (O(h^3)).
  const double tol = order == 1 ? 0.03 : 0.002;
  EXPECT_NEAR(m->area("base") / base, 1.0, tol);
  EXPECT_NEAR(m->area("skin") / skin, 1.0, tol);
  EXPECT_NEAR(m->area("symmetry") / symmetry, 1.0, tol);
  EXPECT_NEAR(m->volume() / volume, 1.0, 1.5 * tol);
  EXPECT_EQ(m->area("suture_abd"), 0.0);
  // The nipple (0, H, 0) is a mesh node of the skin.
  EXPECT_NO_THROW(ObservableProbe(*m, {0.0, H, 0.0}));
  const auto q = mesh_quality(*m->mesh().mesh);
  EXPECT_GT(q.min_dihedral_deg, 5.0);
  EXPECT_LT(q.max_dihedral_deg, 175.0);
  EXPECT_GT(q.min_radius_ratio, 0.1);
  EXPECT_GT(q.mean_radius_ratio, 0.6);
}

INSTANTIATE_TEST_SUITE_P(Shapes, HalfCap,
                         ::testing::Values(CapCase{0.07, 0.06, 1}, CapCase{0.07, 0.06, 2},
                                           CapCase{0.05, 0.02, 1}, CapCase{0.06, 0.08, 1},
                                           CapCase{0.06, 0.08, 2}));

namespace
{
/// Mean edge length of the P1 cap's boundary edges on the base within `band`
/// of the rim (distance to the circle of radius R in y = 0), and elsewhere.
std::pair<double, double> rim_and_other_edges(const meshes::TaggedMesh& tm, double R, double band)
{
  auto node = [&](std::int64_t i) { return &tm.x[3 * i]; };
  auto near_rim = [&](const double* p)
  { return std::abs(p[1]) < 1e-9 && std::abs(std::hypot(p[0], p[2]) - R) < band; };
  double rim = 0, other = 0;
  int n_rim = 0, n_other = 0;
  for (std::size_t f = 0; f < tm.facet_tags.size(); ++f)
    for (int e = 0; e < 3; ++e)
    {
      const double* a = node(tm.facets[3 * f + e]);
      const double* b = node(tm.facets[3 * f + (e + 1) % 3]);
      const double len = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
      if (near_rim(a) && near_rim(b))
        rim += len, ++n_rim;
      else
        other += len, ++n_other;
    }
  return {rim / std::max(n_rim, 1), other / std::max(n_other, 1)};
}
} // namespace

TEST(HalfCapGrading, ElementsShrinkTowardTheRim)
{
  // geometry.rim_size_ratio = 1/3: edges along the rim about a third of
  // mesh_size, the rest of the mesh as before; 1 leaves the mesh uniform.
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0)
    GTEST_SKIP() << "gmsh meshes on rank 0";
  meshes::HalfCapSpec spec;
  spec.mesh_size = 0.012;
  const auto uniform = meshes::mesh_half_cap(spec, 1, 2, 3);
  spec.rim_size_ratio = 1.0 / 3;
  const auto graded = meshes::mesh_half_cap(spec, 1, 2, 3);
  const auto [rim_u, other_u] = rim_and_other_edges(uniform, spec.R, 1e-3);
  const auto [rim_g, other_g] = rim_and_other_edges(graded, spec.R, 1e-3);
  std::cout << "rim edges " << rim_u << " -> " << rim_g << " m, cells " << uniform.num_cells()
            << " -> " << graded.num_cells() << "\n";
  EXPECT_GT(rim_u, 0.7 * spec.mesh_size);
  EXPECT_LT(rim_g, 0.5 * spec.mesh_size);
  EXPECT_GT(rim_g, 0.2 * spec.mesh_size);
  EXPECT_GT(graded.num_cells(), uniform.num_cells());
  EXPECT_LT(graded.num_cells(), 4 * uniform.num_cells());
}
