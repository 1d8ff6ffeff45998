// SPDX-License-Identifier: LGPL-3.0-or-later
#include "sphere_bench.hpp"
#include "mpi_sum.hpp"
#include "tagged_mesh.hpp"
#include "errors.hpp"
#include "mesh_from_gmsh.hpp"
#include "mixed_space.hpp"
#include "residual_newton.hpp"
#include "timer.hpp"
#include "sphere_bench_p1.h"
#include "sphere_bench_p2.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <fmt/format.h>
#include <gmsh.h>
#include <limits>
#include <map>
#include <petscksp.h>
#include <spdlog/spdlog.h>
#include <stdexcept>

namespace breastsim
{
using namespace dolfinx;
using T = PetscScalar;

namespace
{
// Facet tags of verification/forms/sphere_bench.py.
constexpr int tag_inner = 1, tag_outer = 2, tag_plane_x = 3; // planes x, y, z: 3, 4, 5

/// Nominal radial stress P_r and hoop stress P_t (see the header).
std::array<double, 2> nominal_stresses(const SphereBenchSpec& s, double R, double r, double lr)
{
  const double lt = r / R, J = lr * lt * lt;
  return {s.mu * (lr - 1 / lr) + s.lambda * (J - 1) * lt * lt,
          s.mu * (lt - 1 / lt) + s.lambda * (J - 1) * lr * lt};
}

/// lambda_r from P_r at (R, r): P_r is increasing in lambda_r (from -inf at
/// 0+), so Newton safeguarded by bisection.
double radial_stretch(const SphereBenchSpec& s, double R, double r, double P, double guess)
{
  double lo = 1e-8, hi = 1e3, x = guess;
  for (int it = 0; it < 200; ++it)
  {
    const double f = nominal_stresses(s, R, r, x)[0] - P;
    if (std::abs(f) <= 1e-15 * (s.mu + s.lambda))
      return x;
    (f > 0 ? hi : lo) = x;
    const double lt = r / R;
    const double df = s.mu * (1 + 1 / (x * x)) + s.lambda * std::pow(lt, 4);
    double xn = x - f / df;
    if (!(xn > lo && xn < hi))
      xn = 0.5 * (lo + hi);
    if (std::abs(xn - x) <= 1e-15 * x)
      return xn;
    x = xn;
  }
  return x;
}

/// Integrate from A with r(A) = a, P_r(A) = -p0; returns (r(B), P_r(B)).
std::array<double, 2> shoot(const SphereBenchSpec& s, double a, int steps)
{
  const double h = (s.B - s.A) / steps;
  double lr = 1.0;
  // y = (r, P_r): r' = lambda_r(R, r, P_r), P_r' = -2/R (P_r - P_t).
  auto f = [&](double R, std::array<double, 2> y) -> std::array<double, 2>
  {
    lr = radial_stretch(s, R, y[0], y[1], lr);
    const auto P = nominal_stresses(s, R, y[0], lr);
    return {lr, -2 / R * (P[0] - P[1])};
  };
  std::array<double, 2> y{a, -s.p0};
  for (int i = 0; i < steps; ++i)
  {
    const double R = s.A + i * h;
    const auto k1 = f(R, y);
    const auto k2 = f(R + h / 2, {y[0] + h / 2 * k1[0], y[1] + h / 2 * k1[1]});
    const auto k3 = f(R + h / 2, {y[0] + h / 2 * k2[0], y[1] + h / 2 * k2[1]});
    const auto k4 = f(R + h, {y[0] + h * k3[0], y[1] + h * k3[1]});
    for (int k = 0; k < 2; ++k)
      y[k] += h / 6 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
    if (!(y[0] > 0) || !std::isfinite(y[1]))
      return {y[0], std::numeric_limits<double>::quiet_NaN()};
  }
  return y;
}
} // namespace

SphereReference sphere_reference(const SphereBenchSpec& s, int steps)
{
  // P_r(B) increases with a (a larger inner radius stretches the hoops more):
  // bisection on a in [lo, hi].
  double lo = 0.5 * s.A, hi = 4 * s.A;
  if (!(shoot(s, lo, steps)[1] < 0) || !(shoot(s, hi, steps)[1] > 0))
    throw std::runtime_error("sphere_reference: no bracket for the inner radius in [A/2, 4A]");
  for (int it = 0; it < 100 && hi - lo > 1e-15 * s.A; ++it)
  {
    const double m = 0.5 * (lo + hi);
    (shoot(s, m, steps)[1] > 0 ? hi : lo) = m;
  }
  SphereReference ref;
  ref.a = 0.5 * (lo + hi);
  ref.b = shoot(s, ref.a, steps)[0];
  return ref;
}

SphereReference incompressible_sphere_reference(const SphereBenchSpec& s)
{
  // r^3 = R^3 + a^3 - A^3; nominal inner pressure p0 = lambda_a^2 P(a) with the
  // Cauchy pressure P = 2 mu [1/lb - 1/la + 1/(4 lb^4) - 1/(4 la^4)].
  auto outer = [&](double a) { return std::cbrt(std::pow(s.B, 3) + std::pow(a, 3) - std::pow(s.A, 3)); };
  auto nominal_pressure = [&](double a)
  {
    const double la = a / s.A, lb = outer(a) / s.B;
    const double P = 2 * s.mu * (1 / lb - 1 / la + 0.25 / std::pow(lb, 4) - 0.25 / std::pow(la, 4));
    return la * la * P;
  };
  double lo = s.A, hi = 4 * s.A;
  if (!(nominal_pressure(hi) > s.p0) || !(s.p0 >= 0))
    throw std::runtime_error("incompressible_sphere_reference: p0 beyond the range a in [A, 4A]");
  for (int it = 0; it < 200 && hi - lo > 1e-15 * s.A; ++it)
  {
    const double m = 0.5 * (lo + hi);
    (nominal_pressure(m) > s.p0 ? hi : lo) = m;
  }
  SphereReference ref;
  ref.a = 0.5 * (lo + hi);
  ref.b = outer(ref.a);
  return ref;
}

namespace
{
/// The octant A <= |X| <= B, x, y, z >= 0 (rank 0), facets tagged as in
/// verification/forms/sphere_bench.py.
meshes::TaggedMesh octant_shell(const SphereBenchSpec& s, int order, double mesh_size)
{
  meshes::GmshSession session;
  namespace occ = gmsh::model::occ;
  gmsh::vectorpair shell, out;
  std::vector<gmsh::vectorpair> map;
  occ::cut({{3, occ::addSphere(0, 0, 0, s.B)}}, {{3, occ::addSphere(0, 0, 0, s.A)}}, shell, map);
  occ::intersect(shell, {{3, occ::addBox(0, 0, 0, 2 * s.B, 2 * s.B, 2 * s.B)}}, out, map);
  occ::synchronize();
  gmsh::vectorpair ents;
  gmsh::model::getEntities(ents, 3);
  std::vector<int> vols;
  for (auto [d, t] : ents)
    vols.push_back(t);
  gmsh::model::addPhysicalGroup(3, vols, 1);
  gmsh::model::getEntities(ents, 2);
  std::map<int, std::vector<int>> groups;
  // OCC bounding boxes are padded by the geometric tolerance (~1e-7 m): a
  // tolerance relative to the radii, not to the mesh size.
  const double tol = 1e-3 * s.A;
  for (auto [d, t] : ents)
  {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(d, t, x0, y0, z0, x1, y1, z1);
    if (std::abs(x1) < tol)
      groups[tag_plane_x].push_back(t);
    else if (std::abs(y1) < tol)
      groups[tag_plane_x + 1].push_back(t);
    else if (std::abs(z1) < tol)
      groups[tag_plane_x + 2].push_back(t);
    else
      groups[std::max({x1, y1, z1}) < 0.5 * (s.A + s.B) ? tag_inner : tag_outer].push_back(t);
  }
  for (const auto& [tag, faces] : groups)
    gmsh::model::addPhysicalGroup(2, faces, tag);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeMax", mesh_size);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1); // Delaunay: deterministic
  gmsh::option::setNumber("Mesh.Optimize", 1);
  gmsh::option::setNumber("General.NumThreads", 1);
  return meshes::extract_tagged_mesh(order, 0);
}


void check_inputs(const SphereBenchSpec& s, int order, double mesh_size, int load_steps, bool mixed)
{
  if (mixed && (order != 2 || !(s.lambda > 0)))
    throw InputError(fmt::format("sphere benchmark: the mixed formulation is Taylor-Hood P2-P1 with "
                                 "lambda > 0, got order {}, lambda {}", order, s.lambda));
  if (order != 1 && order != 2)
    throw InputError(fmt::format("sphere benchmark: element order must be 1 or 2, got {}", order));
  if (!(s.A > 0 && s.B > s.A && mesh_size > 0 && load_steps >= 1))
    throw InputError("sphere benchmark: need 0 < A < B, mesh_size > 0, load_steps >= 1");
}

/// The compiled forms of verification/forms/sphere_bench.py for P1, P2 or
/// the mixed P2-P1 (coefficient "w").
struct SphereForms
{
  ufcx_function_space* (*space)(const char*);
  const char* coefficient;
  ufcx_form *residual, *jacobian, *ur_inner, *area_inner, *ur_outer, *area_outer;
};

SphereForms sphere_forms(int order, bool mixed)
{
  if (mixed)
    return {functionspace_form_sphere_bench_p2_mixed_residual, "w", form_sphere_bench_p2_mixed_residual,
            form_sphere_bench_p2_mixed_jacobian, form_sphere_bench_p2_mixed_ur_inner,
            form_sphere_bench_p2_bench_area_inner, form_sphere_bench_p2_mixed_ur_outer,
            form_sphere_bench_p2_bench_area_outer};
  if (order == 1)
    return {functionspace_form_sphere_bench_p1_bench_residual, "u", form_sphere_bench_p1_bench_residual,
            form_sphere_bench_p1_bench_jacobian, form_sphere_bench_p1_bench_ur_inner,
            form_sphere_bench_p1_bench_area_inner, form_sphere_bench_p1_bench_ur_outer,
            form_sphere_bench_p1_bench_area_outer};
  return {functionspace_form_sphere_bench_p2_bench_residual, "u", form_sphere_bench_p2_bench_residual,
          form_sphere_bench_p2_bench_jacobian, form_sphere_bench_p2_bench_ur_inner,
          form_sphere_bench_p2_bench_area_inner, form_sphere_bench_p2_bench_ur_outer,
          form_sphere_bench_p2_bench_area_outer};
}

/// Sliding symmetry: u_i = 0 on the plane x_i = 0 (of the mixed space:
/// component i of its displacement, src/model/mixed_space.hpp).
std::vector<std::shared_ptr<const fem::DirichletBC<T>>> symmetry_bcs(const fem::FunctionSpace& V,
                                                                     bool mixed,
                                                                     const TaggedDolfinxMesh& m)
{
  std::vector<std::shared_ptr<const fem::DirichletBC<T>>> bcs;
  for (int i = 0; i < 3; ++i)
  {
    std::vector<std::int32_t> facets;
    for (std::size_t k = 0; k < m.facets->values().size(); ++k)
      if (m.facets->values()[k] == tag_plane_x + i)
        facets.push_back(m.facets->indices()[k]);
    if (mixed)
    {
      bcs.push_back(mixed_displacement_bc(V, facets, i));
      continue;
    }
    auto Vi = V.sub({i});
    auto dofs = fem::locate_dofs_topological(*Vi, 2, facets);
    bcs.push_back(std::make_shared<const fem::DirichletBC<T>>(T(0), std::move(dofs), Vi));
  }
  return bcs;
}

/// The pressure p0 raised to s.p0 in `load_steps` equal increments, Newton
/// to |R| <= 1e-11 |R_load| at each (|R_load| = |R(u)| at the full pressure,
/// from the current u); the Newton iterations over all steps, SolveError if
/// a step does not converge.
int apply_pressure(ResidualNewton& newton, fem::Constant<T>& p0, const SphereBenchSpec& s,
                   int order, int load_steps)
{
  p0.value = {s.p0};
  const double r_load = newton.residual_norm();
  int iterations = 0;
  for (int step = 1; step <= load_steps; ++step)
  {
    p0.value = {s.p0 * step / load_steps};
    ResidualNewtonOptions no;
    no.rtol = 1e-11;
    no.max_iterations = 40;
    no.max_halvings = 20;
    const auto nr = newton.solve(r_load, no, [&](int it, double r) {
      spdlog::debug("sphere bench P{} load {}/{}: Newton {} |R| / |R_load| = {:.3e}", order, step,
                    load_steps, it, r / r_load);
    });
    iterations += nr.iterations;
    if (nr.lu_failed || !(nr.residual <= 1e-11 * r_load))
      throw SolveError(fmt::format("sphere benchmark P{}: Newton did not converge at load step {} "
                                   "(|R| / |R_load| = {:.3e}{})",
                                   order, step, nr.residual / r_load,
                                   nr.lu_failed ? "; the LU solve failed" : ""));
  }
  return iterations;
}
} // namespace

SphereBenchResult solve_sphere_bench(const SphereBenchSpec& s, int order, double mesh_size,
                                     MPI_Comm comm, int load_steps, bool mixed)
{
  Stopwatch stopwatch("sphere benchmark");
  check_inputs(s, order, mesh_size, load_steps, mixed);
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh tm;
  tm.order = order;
  if (rank == 0)
    tm = octant_shell(s, order, mesh_size);
  TaggedDolfinxMesh m = to_dolfinx(comm, tm, order);

  const SphereForms forms = sphere_forms(order, mixed);
  auto V = std::make_shared<fem::FunctionSpace>(
      fem::create_functionspace(forms.space, forms.coefficient, m.mesh));
  auto u = std::make_shared<fem::Function<T>>(V);
  auto p0 = std::make_shared<fem::Constant<T>>(0.0);
  const std::map<std::string, std::shared_ptr<const fem::Constant<T>>> constants{
      {"mu", std::make_shared<fem::Constant<T>>(s.mu)},
      {"lmbda", std::make_shared<fem::Constant<T>>(s.lambda)},
      {"p0", p0}};
  auto create = [&](ufcx_form* f, int rank_)
  {
    std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces(rank_, V);
    return std::make_shared<fem::Form<T>>(fem::create_form<T>(
        *f, spaces, {{forms.coefficient, u}}, constants, {{fem::IntegralType::exterior_facet, m.facets.get()}},
        m.mesh));
  };
  ResidualNewton newton(create(forms.residual, 1), create(forms.jacobian, 2), u,
                        symmetry_bcs(*V, mixed, m));

  SphereBenchResult res;
  res.newton_iterations = apply_pressure(newton, *p0, s, order, load_steps);
  auto scalar = [&](ufcx_form* f) { return mpi_sum(fem::assemble_scalar(*create(f, 0)), comm); };
  res.u_inner = scalar(forms.ur_inner) / scalar(forms.area_inner);
  res.u_outer = scalar(forms.ur_outer) / scalar(forms.area_outer);
  res.cells = m.mesh->topology().index_map(3)->size_global();
  res.dofs = V->dofmap()->index_map->size_global() * V->dofmap()->index_map_bs();
  res.seconds = stopwatch.seconds();
  return res;
}
} // namespace breastsim
