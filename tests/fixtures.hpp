// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Shared helpers for the tests: small meshes and models of the default case.
#include "config.hpp"
#include "model.hpp"
#include "load_stepping.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "simulate.hpp"
#include "surgery.hpp"
#include <dolfinx/la/petsc.h>
#include <algorithm>
#include <cmath>
#include <random>

namespace breastsim::fixtures
{
/// A coarse default case (fast), optionally of element order 2.
inline Config coarse_case(int order = 1, double h = 0.014)
{
  Config c;
  c.set("geometry.mesh_size", h);
  c.set("geometry.order", std::int64_t(order));
  c.validate();
  return c;
}

/// Largest difference max_i |a_i - b_i| of two fields and the size max_i |b_i|
/// of the reference b (same length).
struct MaxDifference
{
  double diff = 0, size = 0;
};
template <class A, class B>
inline MaxDifference max_difference(const A& a, const B& b)
{
  MaxDifference d;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    d.diff = std::max(d.diff, std::abs(a[i] - b[i]));
    d.size = std::max(d.size, std::abs(b[i]));
  }
  return d;
}

/// Model of a case with its parameters bound.
inline std::unique_ptr<Model> make_model(const Config& c)
{
  auto m = std::make_unique<Model>(build_neutral_mesh(c, MPI_COMM_WORLD),
                                   Constraints{true, c.flag("base.fixed")});
  apply_parameters(c, *m);
  return m;
}

/// Model of the remaining body after the case's incision (suture faces tagged).
std::unique_ptr<Model> make_incised_model(const Config& c);

/// Fill u with dilation * X plus a smooth random-ish field of amplitude `amp`
/// (constrained dofs zeroed).
inline void perturb(Model& m, double amp, unsigned seed, double dilation = 0)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  const double a[9] = {d(gen), d(gen), d(gen), d(gen), d(gen), d(gen), d(gen), d(gen), d(gen)};
  m.displacement()->interpolate(
      [&](auto&& x)
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(3), x.shape(1)});
        for (std::size_t p = 0; p < x.shape(1); ++p)
          for (int i = 0; i < 3; ++i)
            v(i, p) = dilation * x(i, p) + amp * (a[3 * i] * std::sin(20 * x(0, p)) + a[3 * i + 1] * std::cos(15 * x(1, p))
                             + a[3 * i + 2] * x(2, p) * 10);
        return v;
      });
  m.constrain_displacement(); // u = g (= 0) on constrained dofs
}
} // namespace breastsim::fixtures

namespace breastsim::fixtures
{
/// Solve the model under gravity vector g from u = 0 (default solver settings).
inline LoadPathReport solve_gravity(Model& m, std::array<double, 3> g, NewtonOptions o = {})
{
  NewtonSolver newton(m, o);
  m.displacement()->x()->set(0.0);
  const double f = set_gravity(m, g);
  return continuation(m, newton, "load", 0.0, 1.0, LoadStepOptions{}, "test", f);
}

/// Largest |u| component over all ranks.
inline double max_abs_u(const Model& m)
{
  double local = 0;
  for (double x : m.displacement()->x()->array())
    local = std::max(local, std::abs(x));
  double global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return global;
}
} // namespace breastsim::fixtures

namespace breastsim::fixtures
{
inline std::unique_ptr<Model> make_incised_model(const Config& c)
{
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  meshes::TaggedMesh tm;
  const int order = static_cast<int>(c.integer("geometry.order"));
  tm.order = order;
  if (rank == 0)
    tm = meshes::mesh_incised_cap(HalfCapSpec::from(c), IncisionSpec::from(c), {1, 2, 3, 4, 5});
  auto m = std::make_unique<Model>(to_dolfinx(MPI_COMM_WORLD, tm, order));
  apply_parameters(c, *m);
  return m;
}
} // namespace breastsim::fixtures
