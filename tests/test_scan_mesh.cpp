// SPDX-License-Identifier: LGPL-3.0-or-later
// The mesh of a scan (src/scan/scan_mesh.hpp) as a full breast in the
// model: a cap's scan, fitted and meshed, has the cap's volume and base
// perimeter measured as they are (not mirrored, the rim closed), its nipple
// as a skin node; --half gives the mirrored half with the same observables.
#include "breastsim_registry.hpp"
#include "mesh_from_gmsh.hpp"
#include "model.hpp"
#include "observables.hpp"
#include "scan_fixtures.hpp"
#include "scan_model.hpp"
#include <gtest/gtest.h>

using namespace scan_fixtures;

namespace
{
breastsim::Observables observe(const ScanModel& m, bool half)
{
  using namespace breastsim;
  const ScanMesh mesh = mesh_scan(m.fit, m.fit.radius(Vec3{0, 1, 0}) * Vec3{0, 1, 0}, {0.01, 1, half},
                                  generated::tag("base"), generated::tag("skin"), generated::tag("symmetry"));
  Model model(to_dolfinx(MPI_COMM_WORLD, mesh.mesh, 1));
  const ObservableProbe probe(model, mesh.nipple);
  return probe.measure(model);
}
} // namespace

TEST(ScanMesh, AFullBreastIsMeasuredAsItIsAndAHalfMirrored)
{
  int size;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1)
    GTEST_SKIP() << "serial: the mesh is built on each rank";
  const ScanModel m = fit_scan(cap_scan(), nullptr, {});
  const double volume = M_PI * 0.06 * 0.06 * (3 * (0.07 * 0.07 + 0.06 * 0.06) / 0.12 - 0.06) / 3; // 574.9 cm^3
  for (bool half : {false, true})
  {
    const breastsim::Observables o = observe(m, half);
    EXPECT_NEAR(o.volume, volume, 0.01 * volume) << (half ? "half" : "full");
    EXPECT_NEAR(o.base_perimeter, 2 * M_PI * 0.07, 0.01 * 2 * M_PI * 0.07) << (half ? "half" : "full");
    EXPECT_NEAR(o.nipple[1], 0.06, 1e-4);
    EXPECT_NEAR(o.nipple[0], 0.0, 1e-9);
  }
}
