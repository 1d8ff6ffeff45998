// SPDX-License-Identifier: LGPL-3.0-or-later
// Mesh morphing of the neutral cap for the calibration of R and H
// (src/mesh/cap_morph.hpp, calibrate/forward/forward_model.hpp): the morphed mesh is
// the new cap (skin on the new sphere, base in y = 0, symmetry face in
// x = 0), no element inverts, and the observables are smooth in R and H
// (central differences with two step sizes agree).
#include "cap_morph.hpp"
#include "half_cap.hpp"
#include "fit_parameters.hpp"
#include "forward_model.hpp"
#include <cmath>
#include <gtest/gtest.h>
#include <set>

using namespace breastsim;

namespace
{
constexpr int tag_base = 1, tag_skin = 2, tag_sym = 3;

std::set<std::int64_t> nodes_tagged(const meshes::TaggedMesh& m, int tag)
{
  std::set<std::int64_t> s;
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
    if (m.facet_tags[f] == tag)
      for (std::size_t k = 0; k < m.nodes_per_facet(); ++k)
        s.insert(m.facets[f * m.nodes_per_facet() + k]);
  return s;
}

/// Signed volume of tetrahedron c (corner nodes 0..3).
double tet_volume(const meshes::TaggedMesh& m, std::size_t c)
{
  const auto* n = &m.cells[c * m.nodes_per_cell()];
  auto p = [&](int k, int i) { return m.x[3 * n[k] + i]; };
  double a[3][3];
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i)
      a[k][i] = p(k + 1, i) - p(0, i);
  return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
          - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
          + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
         / 6;
}
} // namespace

TEST(CalibrateMorph, MorphedCapIsTheNewCap)
{
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0)
    GTEST_SKIP() << "gmsh meshes on rank 0";
  for (int order : {1, 2})
  {
    meshes::HalfCapSpec spec; // R = 70 mm, H = 60 mm
    spec.mesh_size = 0.014;
    spec.order = order;
    const meshes::TaggedMesh m0 = meshes::mesh_half_cap(spec, tag_base, tag_skin, tag_sym);
    const auto skin = nodes_tagged(m0, tag_skin), base = nodes_tagged(m0, tag_base),
               sym = nodes_tagged(m0, tag_sym);
    ASSERT_GT(skin.size(), 50u);
    // Flatter, taller than a hemisphere (H > R), and smaller caps.
    for (const meshes::CapShape to : {meshes::CapShape{0.08, 0.05}, meshes::CapShape{0.06, 0.075},
                                      meshes::CapShape{0.056, 0.048}})
    {
      meshes::TaggedMesh m = m0;
      meshes::morph_cap(m.x, {spec.R, spec.H}, to);
      const double Rs = meshes::sphere_radius(to.R, to.H), yc = to.H - Rs;
      double skin_err = 0, base_err = 0, sym_err = 0, rim_err = 0;
      for (auto n : skin)
      {
        const double x = m.x[3 * n], y = m.x[3 * n + 1], z = m.x[3 * n + 2];
        skin_err = std::max(skin_err, std::abs(std::hypot(x, y - yc, z) - Rs));
      }
      for (auto n : base)
      {
        base_err = std::max(base_err, std::abs(m.x[3 * n + 1]));
        if (skin.count(n)) // the rim: the circle of radius R in y = 0
          rim_err = std::max(rim_err, std::abs(std::hypot(m.x[3 * n], m.x[3 * n + 2]) - to.R));
      }
      for (auto n : sym)
        sym_err = std::max(sym_err, std::abs(m.x[3 * n]));
      const double scale = to.R + to.H;
      EXPECT_LT(skin_err, 1e-12 * scale) << "order " << order << " R " << to.R << " H " << to.H;
      EXPECT_LT(base_err, 1e-12 * scale);
      EXPECT_LT(sym_err, 1e-12 * scale);
      EXPECT_LT(rim_err, 1e-12 * scale);
      // The apex (nipple) node goes to (0, H, 0).
      double apex = 1;
      for (auto n : skin)
        apex = std::min(apex, std::hypot(m.x[3 * n], m.x[3 * n + 1] - to.H, m.x[3 * n + 2]));
      EXPECT_LT(apex, 1e-12 * scale);
      // No element inverts, none collapses (volume ratio to the original in a band).
      double qmin = 1e9, qmax = 0;
      for (std::size_t c = 0; c < m.num_cells(); ++c)
      {
        const double q = tet_volume(m, c) / tet_volume(m0, c);
        qmin = std::min(qmin, q);
        qmax = std::max(qmax, q);
      }
      EXPECT_GT(qmin, 0.2);
      EXPECT_LT(qmax, 5.0);
      // Morphing back restores the generated mesh to round-off.
      meshes::morph_cap(m.x, to, {spec.R, spec.H});
      for (std::size_t i = 0; i < m.x.size(); ++i)
        ASSERT_NEAR(m.x[i], m0.x[i], 1e-14) << "coordinate " << i;
    }
  }
}

TEST(CalibrateMorph, ObservablesAreSmoothInRAndH)
{
  // d(observable)/d(ln p) by central differences with steps 1e-3 and 2e-3
  // in ln p: for a smooth map they agree to O(h^2) (here within 1 % of the
  // largest derivative of the posture); with remeshing they do not (the
  // mesh topology jumps).
  Config c;
  c.set("geometry.mesh_size", 0.016);
  c.set("postures.names", std::vector<std::string>{"standing"});
  c.validate();
  calibration::ForwardModel fm({named_posture("standing")}, MPI_COMM_WORLD, true);
  auto observe = [&](const std::string& key, double lnp)
  {
    Config k = c;
    k.set(key, std::exp(lnp));
    k.validate();
    const Observables o = fm.solve(k)[0];
    return std::vector<double>{o.projection, o.z_min, o.z_max, o.nipple[1], o.nipple[2],
                               o.base_perimeter};
  };
  for (const std::string key : {"geometry.R", "geometry.H"})
  {
    const double y0 = std::log(c.number(key));
    std::vector<std::vector<double>> d; // d[s][i] for steps h_s
    for (double h : {1e-3, 2e-3})
    {
      const auto p = observe(key, y0 + h), m = observe(key, y0 - h);
      std::vector<double> di;
      for (std::size_t i = 0; i < p.size(); ++i)
        di.push_back((p[i] - m[i]) / (2 * h));
      d.push_back(di);
    }
    double scale = 0;
    for (double x : d[0])
      scale = std::max(scale, std::abs(x));
    ASSERT_GT(scale, 0.01) << key; // observables move by centimetres per unit ln p
    for (std::size_t i = 0; i < d[0].size(); ++i)
      EXPECT_NEAR(d[0][i], d[1][i], 0.01 * scale) << key << " observable " << i;
  }
  EXPECT_EQ(fm.meshes_built(), 1);
  EXPECT_GT(fm.morphs(), 6);
}
