// SPDX-License-Identifier: LGPL-3.0-or-later
// Each energy term at a homogeneous deformation equals its closed form.
#include "half_cap.hpp"
#include "fixtures.hpp"
#include <gtest/gtest.h>

using namespace breastsim;

namespace
{
/// u = (F0 - I) X + a
void set_homogeneous(Model& m, const std::array<double, 9>& F0, const std::array<double, 3>& a = {})
{
  m.displacement()->interpolate(
      [&](auto&& x)
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(3), x.shape(1)});
        for (std::size_t p = 0; p < x.shape(1); ++p)
          for (int i = 0; i < 3; ++i)
          {
            v(i, p) = a[i];
            for (int j = 0; j < 3; ++j)
              v(i, p) += (F0[3 * i + j] - (i == j)) * x(j, p);
          }
        return v;
      });
}

double det3(const std::array<double, 9>& F)
{
  return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6])
         + F[2] * (F[3] * F[7] - F[4] * F[6]);
}

/// eq. (5): W = mu/2 (tr F F^T - 3 - 2 ln J) + lambda/2 (J - 1)^2
double neo_hooke_density(const std::array<double, 9>& F, double mu, double lmbda)
{
  double trFFt = 0;
  for (double f : F)
    trFFt += f * f;
  const double J = det3(F);
  return mu / 2 * (trFFt - 3 - 2 * std::log(J)) + lmbda / 2 * (J - 1) * (J - 1);
}

class Energies : public ::testing::TestWithParam<int>
{
protected:
  void SetUp() override
  {
    c = fixtures::coarse_case(GetParam(), 0.012);
    m = fixtures::make_model(c);
  }
  Config c;
  std::unique_ptr<Model> m;
};
} // namespace

TEST_P(Energies, TissueNeoHookean)
{
  const std::array<double, 9> F0 = {1.1, 0.2, 0.0, -0.05, 0.9, 0.1, 0.0, 0.03, 1.05};
  set_homogeneous(*m, F0);
  const double mu = 1300, lmbda = 7000;
  m->set_parameter("mu", {mu});
  m->set_parameter("lmbda", {lmbda});
  const double J = det3(F0);
  const double W = neo_hooke_density(F0, mu, lmbda);
  const double V = m->volume() / J; // reference volume of the mesh
  EXPECT_NEAR(m->energy("tissue") / (W * V), 1.0, 1e-10);
}

TEST_P(Energies, GravityPotential)
{
  // u = a (constant): E = -rho g.a V.
  const std::array<double, 3> a = {0.0, 0.004, -0.01}, g = {0.0, -3.0, -9.0};
  set_homogeneous(*m, {1, 0, 0, 0, 1, 0, 0, 0, 1}, a);
  m->set_parameter("rho", {1000.0});
  m->set_parameter("g_vec", {g[0], g[1], g[2]});
  m->set_parameter("load", {0.5});
  const double V = m->volume();
  const double expected = -1000.0 * 0.5 * (g[0] * a[0] + g[1] * a[1] + g[2] * a[2]) * V;
  // (P2: the volume functional and the load use different quadrature degrees.)
  EXPECT_NEAR(m->energy("gravity") / expected, 1.0, 1e-8);
}

TEST_P(Energies, SkinMembraneUnderDilation)
{
  // F = s I: C_s = s^2 P (both surface stretches s), J_s = s^2.
  const double mu_s = 40000, lmbda_s = 25000, t = 0.002;
  m->set_parameter("mu_s", {mu_s});
  m->set_parameter("lmbda_s", {lmbda_s});
  m->set_parameter("t_s", {t});
  const double A = m->area("skin");
  for (double s : {1.08, 0.93})
  {
    set_homogeneous(*m, {s, 0, 0, 0, s, 0, 0, 0, s});
    const double Js = s * s;
    const double W = mu_s / 2 * (2 * s * s - 2 - 2 * std::log(Js)) + lmbda_s / 2 * (Js - 1) * (Js - 1);
    m->set_parameter("skin_tension_only", {0.0});
    EXPECT_NEAR(m->energy("skin") / (t * W * A), 1.0, 1e-10) << "plain, s = " << s;
    // Relaxed law: identical in tension; for exactly equal surface stretches
    // (degenerate principal directions) it falls back to the plain law.
    m->set_parameter("skin_tension_only", {1.0});
    EXPECT_NEAR(m->energy("skin") / (t * W * A), 1.0, 1e-10) << "relaxed, s = " << s;
  }
  // Compression with distinct stretches: the relaxed skin is slack (W = 0).
  set_homogeneous(*m, {0.90, 0, 0, 0, 0.95, 0, 0, 0, 0.92});
  m->set_parameter("skin_tension_only", {0.0});
  const double plain = m->energy("skin");
  m->set_parameter("skin_tension_only", {1.0});
  EXPECT_GT(plain, 0.0);
  EXPECT_LT(m->energy("skin"), 1e-9 * plain);
}

TEST_P(Energies, SkinRelaxedIsTheLowerEnvelope)
{
  // Under a uniaxial stretch the cap's skin has every orientation: parts are
  // taut, parts wrinkled. The relaxed energy is positive and lies below the
  // plain membrane energy (it drops the compressive part).
  const double mu_s = 40000, lmbda_s = 25000;
  m->set_parameter("mu_s", {mu_s});
  m->set_parameter("lmbda_s", {lmbda_s});
  // Uniaxial stretch along y with lateral contraction: on the cap the skin
  // has every orientation, so parts are taut and parts are wrinkled.
  set_homogeneous(*m, {0.85, 0, 0, 0, 1.2, 0, 0, 0, 0.85});
  m->set_parameter("skin_tension_only", {0.0});
  const double plain = m->energy("skin");
  m->set_parameter("skin_tension_only", {1.0});
  const double relaxed = m->energy("skin");
  EXPECT_GT(relaxed, 0.0);
  EXPECT_LT(relaxed, plain); // the relaxed energy is the lower envelope
}

TEST_P(Energies, SkinUpperPoleIsTheSkinLawOnTheUpperHalf)
{
  // F = s I with equal moduli: the upper-pole term is the skin's energy over
  // the skin with Z > 0, half the cap's skin (symmetric in z). Facets cut by
  // Z = 0 are counted by their quadrature points: O(h) in the area.
  const double mu = 40000, lmbda = 25000, t = 0.002, s = 1.08;
  m->set_parameter("mu_s", {mu});
  m->set_parameter("lmbda_s", {lmbda});
  m->set_parameter("mu_u", {mu});
  m->set_parameter("lmbda_u", {lmbda});
  m->set_parameter("t_s", {t});
  set_homogeneous(*m, {s, 0, 0, 0, s, 0, 0, 0, s});
  const double Js = s * s;
  const double W = mu / 2 * (2 * s * s - 2 - 2 * std::log(Js)) + lmbda / 2 * (Js - 1) * (Js - 1);
  const double expected = t * W * m->area("skin") / 2;
  EXPECT_NEAR(m->energy("skin_upper_pole") / expected, 1.0, GetParam() == 1 ? 0.03 : 0.01);
  EXPECT_NEAR(m->energy("skin_upper_pole") / m->energy("skin"), 0.5, GetParam() == 1 ? 0.015 : 0.005);
  // Its own moduli: W is linear in (mu, lambda).
  m->set_parameter("mu_u", {2 * mu});
  m->set_parameter("lmbda_u", {2 * lmbda});
  EXPECT_NEAR(m->energy("skin_upper_pole") / expected, 2.0, GetParam() == 1 ? 0.06 : 0.02);
  // Compression with distinct stretches: slack like the skin (W = 0).
  set_homogeneous(*m, {0.90, 0, 0, 0, 0.95, 0, 0, 0, 0.92});
  EXPECT_LT(m->energy("skin_upper_pole"), 1e-9 * expected);
}

TEST_P(Energies, BaseSprings)
{
  // u = a on the base: E = c/2 |a|^2 int (1 + (k - 1) max(0, -Z)/R) dA and
  // int_{half disc, Z < 0} (-Z) dA = R^3 / 3.
  const std::array<double, 3> a = {0.001, -0.002, 0.003};
  set_homogeneous(*m, {1, 0, 0, 0, 1, 0, 0, 0, 1}, a);
  const double c0 = 3e5, k = 4.0, R = c.number("geometry.R");
  const double a2 = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  m->set_parameter("c", {c0});
  m->set_parameter("c_fold_ratio", {1.0});
  EXPECT_NEAR(m->energy("base_springs") / (c0 / 2 * a2 * m->area("base")), 1.0, 1e-10);
  m->set_parameter("c_fold_ratio", {k});
  const double expected = c0 / 2 * a2 * (M_PI * R * R / 2 + (k - 1) / R * R * R * R / 3);
  // The mesh's base is a polygon inscribed in the circle: O(h^2) area error.
  EXPECT_NEAR(m->energy("base_springs") / expected, 1.0, GetParam() == 1 ? 0.01 : 1e-3);
}

TEST_P(Energies, SuspensoryLigament)
{
  // u = a on the skin: E = k_l/2 |a|^2 x (skin area with Z > 0) = half the
  // skin (the cap is symmetric in z). Facets cut by Z = 0 are counted by
  // their quadrature points: O(h) in the area.
  const std::array<double, 3> a = {0.001, -0.002, 0.003};
  set_homogeneous(*m, {1, 0, 0, 0, 1, 0, 0, 0, 1}, a);
  const double k = 1500;
  m->set_parameter("k_l", {k});
  const double expected = k / 2 * (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * m->area("skin") / 2;
  EXPECT_NEAR(m->energy("suspensory_ligament") / expected, 1.0, GetParam() == 1 ? 0.03 : 0.01);
}

TEST_P(Energies, SuspensoryCables)
{
  // u = e (X - A(X)) = e (0, Y, -d): every cable lengthens by e |X - A|, so
  // E = k/2 e^2 int_{skin, Z > 0} (Y^2 + d^2) dA. On the sphere of radius Rs
  // the band [Y, Y + dY] has area pi Rs dY on the half cap (Archimedes),
  // half of it at Z > 0: E = k/2 e^2 pi Rs / 2 (H^3 / 3 + d^2 H).
  const double k = 1500, d = 0.02, e = 0.05;
  const double H = c.number("geometry.H"), R = c.number("geometry.R");
  const double Rs = (R * R + H * H) / (2 * H);
  m->set_parameter("k_c", {k});
  m->set_parameter("d_a", {d});
  set_homogeneous(*m, {1, 0, 0, 0, 1 + e, 0, 0, 0, 1}, {0.0, 0.0, -e * d});
  const double expected = k / 2 * e * e * M_PI * Rs / 2 * (H * H * H / 3 + d * d * H);
  EXPECT_NEAR(m->energy("suspensory_cables") / expected, 1.0, GetParam() == 1 ? 0.03 : 0.01);
  // Toward the anchors the cables go slack: no energy.
  set_homogeneous(*m, {1, 0, 0, 0, 1 - e, 0, 0, 0, 1}, {0.0, 0.0, e * d});
  EXPECT_EQ(m->energy("suspensory_cables"), 0.0);
}

TEST_P(Energies, ChestWall)
{
  // u = (0, -a, 0): the skin below height a goes a - Y behind the chest.
  // On the sphere of radius Rs the band [Y, Y + dY] has area pi Rs dY on the
  // half cap (Archimedes), so E = k/2 pi Rs int_0^a (a - Y)^2 dY
  // = k pi Rs a^3 / 6. The faceted skin integrates the kinked density to O(h).
  const double k = 2e7, H = c.number("geometry.H"), R = c.number("geometry.R");
  const double a = 0.6 * H, Rs = (R * R + H * H) / (2 * H);
  m->set_parameter("k_w", {k});
  set_homogeneous(*m, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0.0, -a, 0.0});
  EXPECT_NEAR(m->energy("chest_wall") / (k * M_PI * Rs * a * a * a / 6), 1.0,
              GetParam() == 1 ? 0.05 : 0.01);
  // In front of the chest (u_y > 0 everywhere) the wall does nothing.
  set_homogeneous(*m, {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0.002, 0.0005, -0.003});
  EXPECT_EQ(m->energy("chest_wall"), 0.0);
}

TEST_P(Energies, GlandCore)
{
  // Homogeneous F0: E = m_g W(F0) x V_core, V_core = volume of the half cap
  // inside the cylinder x^2 + z^2 < r^2 around the nipple axis:
  //   V_core = pi [ (Rs^3 - (Rs^2 - r^2)^(3/2)) / 3 - (Rs - H) r^2 / 2 ],
  // Rs = (R^2 + H^2) / (2 H) the sphere radius. Cells are counted by their
  // quadrature points: O(h) in the volume.
  const std::array<double, 9> F0 = {1.05, 0.02, 0.0, 0.0, 0.97, 0.01, 0.0, 0.0, 1.02};
  set_homogeneous(*m, F0);
  const double mu = 500, lmbda = 6000, mg = 3, r = 0.03;
  m->set_parameter("mu", {mu});
  m->set_parameter("lmbda", {lmbda});
  m->set_parameter("m_g", {mg});
  m->set_parameter("r_g", {r});
  const double W = neo_hooke_density(F0, mu, lmbda);
  const double R = c.number("geometry.R"), H = c.number("geometry.H");
  const double Rs = (R * R + H * H) / (2 * H);
  const double V = M_PI * ((Rs * Rs * Rs - std::pow(Rs * Rs - r * r, 1.5)) / 3 - (Rs - H) * r * r / 2);
  EXPECT_NEAR(m->energy("gland_core") / (mg * W * V), 1.0, 0.05);
}

TEST_P(Energies, GlandLobe)
{
  // Homogeneous F0: E = m_l W(F0) int w dV with w = max(1 - rho^2, 0)^2 on
  // the ellipsoid rho < 1 (radius a, half-depth b, centre height y = b: it
  // lies inside the cap and touches the base at one point). Over the half
  // ellipsoid X > 0, int w dV = 1/2 a^2 b 4 pi int_0^1 (1 - s^2)^2 s^2 ds
  // = 16 pi a^2 b / 105. Cells are integrated at their quadrature points.
  const std::array<double, 9> F0 = {1.05, 0.02, 0.0, 0.0, 0.97, 0.01, 0.0, 0.0, 1.02};
  set_homogeneous(*m, F0);
  const double mu = 500, lmbda = 6000, ml = 3, a = 0.035, b = 0.02;
  m->set_parameter("mu", {mu});
  m->set_parameter("lmbda", {lmbda});
  m->set_parameter("m_l", {ml});
  m->set_parameter("y_l", {b});
  m->set_parameter("a_l", {a});
  m->set_parameter("b_l", {b});
  const double W = neo_hooke_density(F0, mu, lmbda);
  const double weight_volume = 16 * M_PI * a * a * b / 105;
  EXPECT_NEAR(m->energy("gland_lobe") / (ml * W * weight_volume), 1.0, 0.05);
  // Lifted out of the cap the lobe holds no tissue: no energy.
  m->set_parameter("y_l", {1.0});
  EXPECT_EQ(m->energy("gland_lobe"), 0.0);
}

TEST_P(Energies, TissueField)
{
  // Homogeneous F0. (a) Basis functions wider than the body by 1e3: s is
  // the constant sum of the amplitudes (to 1e-6), so
  //   E_field = (exp(a_1 + a_2) - 1) E_tissue.
  // (b) One Gaussian of width w centred on the symmetry plane deep inside
  // the cap: over the half space x > 0,
  //   int (exp(a exp(-r^2 / 2 w^2)) - 1) dV = 1/2 sum_n a^n / n! (2 pi w^2 / n)^(3/2);
  // the quadrature resolves the bump on this mesh to a few per cent.
  const std::array<double, 9> F0 = {1.05, 0.02, 0.0, 0.0, 0.97, 0.01, 0.0, 0.0, 1.02};
  set_homogeneous(*m, F0);
  const double mu = 500, lmbda = 6000;
  m->set_parameter("mu", {mu});
  m->set_parameter("lmbda", {lmbda});
  std::vector<double> a(24, 0.0), centres(72, 0.0);
  a[0] = 0.4;
  a[1] = -0.1;
  m->set_parameter("a_field", a);
  m->set_parameter("c_field", centres);
  m->set_parameter("w_field", {100.0});
  EXPECT_NEAR(m->energy("tissue_field") / m->energy("tissue"), std::exp(0.3) - 1, 1e-6);

  const double w = 0.008, a1 = 0.7;
  a.assign(24, 0.0);
  a[0] = a1;
  centres[1] = 0.025; // (0, 25 mm, 0)
  m->set_parameter("a_field", a);
  m->set_parameter("c_field", centres);
  m->set_parameter("w_field", {w});
  double integral = 0, term = 1;
  for (int n = 1; n < 30; ++n)
  {
    term *= a1 / n;
    integral += 0.5 * term * std::pow(2 * M_PI * w * w / n, 1.5);
  }
  const double W = neo_hooke_density(F0, mu, lmbda);
  EXPECT_NEAR(m->energy("tissue_field") / (W * integral), 1.0, 0.05);
}

TEST_P(Energies, TissueLaw)
{
  // Homogeneous F0: E = V sum_k b_k f_k(F0), and E_tissue = V W(F0), so
  // E_law / E_tissue = sum_k b_k f_k / W with I1b = J^(-2/3) tr C,
  // I2b = J^(-4/3) (tr(C)^2 - tr(C^2)) / 2.
  const std::array<double, 9> F0 = {1.1, 0.05, 0.0, 0.0, 0.92, 0.03, 0.02, 0.0, 1.04};
  set_homogeneous(*m, F0);
  const double mu = 500, lmbda = 6000;
  m->set_parameter("mu", {mu});
  m->set_parameter("lmbda", {lmbda});
  const std::vector<double> b = {300, 80, 40};
  m->set_parameter("b_law", b);
  double C[9] = {}; // C = F^T F
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        C[3 * i + j] += F0[3 * k + i] * F0[3 * k + j];
  double trC = C[0] + C[4] + C[8], trC2 = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      trC2 += C[3 * i + j] * C[3 * j + i];
  const double J = det3(F0), i1 = std::pow(J, -2.0 / 3) * trC - 3,
               i2 = std::pow(J, -4.0 / 3) * (trC * trC - trC2) / 2 - 3;
  const double law = b[0] * i1 * i1 + b[1] * i1 * i1 * i1 + b[2] * i2;
  EXPECT_NEAR(m->energy("tissue_law") / m->energy("tissue"), law / neo_hooke_density(F0, mu, lmbda), 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Orders, Energies, ::testing::Values(1, 2),
                         [](const auto& info) { return "P" + std::to_string(info.param); });
