// SPDX-License-Identifier: LGPL-3.0-or-later
// fold_site (src/jobs/surgery.hpp): where a deformation is closest to
// folding, on P1 and P2 cells with a vertex pushed through its cell.
#include "fixtures.hpp"
#include "surgery.hpp"
#include <gtest/gtest.h>
#include <cmath>

using namespace breastsim;

namespace
{
/// Push the first corner of local cell 0 through the plane of its opposite
/// face (to its mirror image); returns the corner's reference position.
std::array<double, 3> push_corner_through(Model& m)
{
  auto dofs = m.space()->dofmap()->cell_dofs(0);
  const auto X = m.space()->tabulate_dof_coordinates(false);
  auto p = [&](int k) { return std::array<double, 3>{X[3 * dofs[k]], X[3 * dofs[k] + 1], X[3 * dofs[k] + 2]}; };
  const auto a = p(0), b = p(1), c = p(2), d = p(3);
  // n = (c - b) x (d - b); distance of a to the plane of b, c, d along n.
  const std::array<double, 3> e1 = {c[0] - b[0], c[1] - b[1], c[2] - b[2]}, e2 = {d[0] - b[0], d[1] - b[1], d[2] - b[2]};
  std::array<double, 3> n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  double dist = 0;
  for (int i = 0; i < 3; ++i)
    dist += (a[i] - b[i]) * n[i] / nn;
  auto u = m.displacement()->x()->mutable_array();
  std::fill(u.begin(), u.end(), 0.0);
  for (int i = 0; i < 3; ++i)
    u[3 * dofs[0] + i] = -2 * dist * n[i] / nn; // a -> its mirror image in the face plane
  m.displacement()->x()->scatter_fwd();
  return a;
}
} // namespace

TEST(FoldSite, FindsTheCellAroundAnInvertedCorner)
{
  int size;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    GTEST_SKIP() << "serial: the pushed corner is local cell 0 of rank 0";
  for (int order : {1, 2})
  {
    Config c = fixtures::coarse_case(order, 0.014);
    auto m = fixtures::make_incised_model(c);
    const FoldSite rest = fold_site(*m);
    EXPECT_NEAR(rest.det_min, 1.0, 1e-12) << "P" << order;
    EXPECT_NEAR(rest.det_centroid, 1.0, 1e-12) << "P" << order;
    const auto corner = push_corner_through(*m);
    const FoldSite f = fold_site(*m);
    EXPECT_LT(f.det_min, 0.0) << "P" << order;
    EXPECT_NEAR(f.det_min, m->min_detF(), 1e-12) << "P" << order; // the same points as the line search checks
    // The folded cell touches the pushed corner: its centroid lies within a
    // cell size (the mesh size; 1.5x for gmsh's spread) of it.
    const double d = std::hypot(f.x[0] - corner[0], f.x[1] - corner[1], f.x[2] - corner[2]);
    EXPECT_LT(d, 1.5 * 0.014) << "P" << order;
  }
}
