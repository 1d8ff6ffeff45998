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
