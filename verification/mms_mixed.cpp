// SPDX-License-Identifier: LGPL-3.0-or-later
#include "mms_mixed.hpp"
#include "mpi_sum.hpp"
#include "errors.hpp"
#include "geometry_options.hpp"
#include "mixed_space.hpp"
#include "residual_newton.hpp"
#include "breastsim_registry.hpp"
#include "timer.hpp"
#include "mms_mixed_p1.h"
#include "mms_mixed_p2.h"
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace breastsim
{
using namespace dolfinx;
using T = PetscScalar;

namespace
{
/// The compiled forms of verification/forms/mms_mixed.py for one
/// formulation: the space factory, its coefficient's name, residual,
/// Jacobian, the u errors (and the p error, mixed only) and the norms.
struct IncompressibleForms
{
  ufcx_function_space* (*space)(const char*);
  const char* coefficient;
  ufcx_form *residual, *jacobian, *error_l2, *error_h1, *error_p, *norm_l2, *norm_h1, *norm_p;
};

IncompressibleForms incompressible_forms(bool mixed, int order)
{
  if (mixed)
    return {functionspace_form_mms_mixed_p2_mixed_residual, "w", form_mms_mixed_p2_mixed_residual,
            form_mms_mixed_p2_mixed_jacobian, form_mms_mixed_p2_mixed_error_l2,
            form_mms_mixed_p2_mixed_error_h1, form_mms_mixed_p2_mixed_error_p,
            form_mms_mixed_p2_norm_l2, form_mms_mixed_p2_norm_h1, form_mms_mixed_p2_norm_p};
  if (order == 1)
    return {functionspace_form_mms_mixed_p1_disp_residual, "u", form_mms_mixed_p1_disp_residual,
            form_mms_mixed_p1_disp_jacobian, form_mms_mixed_p1_disp_error_l2,
            form_mms_mixed_p1_disp_error_h1, nullptr, form_mms_mixed_p1_norm_l2,
            form_mms_mixed_p1_norm_h1, nullptr};
  return {functionspace_form_mms_mixed_p2_disp_residual, "u", form_mms_mixed_p2_disp_residual,
          form_mms_mixed_p2_disp_jacobian, form_mms_mixed_p2_disp_error_l2,
          form_mms_mixed_p2_disp_error_h1, nullptr, form_mms_mixed_p2_norm_l2,
          form_mms_mixed_p2_norm_h1, nullptr};
}

void check_request(const Config& c, bool mixed, int order)
{
  if (order != 1 && order != 2)
    throw InputError(fmt::format("incompressible MMS: element order must be 1 or 2, got {}", order));
  if (mixed && order != 2)
    throw InputError(fmt::format("key 'tissue.formulation' = \"mixed\" is Taylor-Hood P2-P1: it needs "
                                 "element order 2, got {}", order));
  if (mixed && !(c.number("tissue.lambda") > 0))
    throw InputError(fmt::format("key 'tissue.lambda' = {} with tissue.formulation = \"mixed\": the "
                                 "pressure equation (J - 1) - p / lambda = 0 needs lambda > 0",
                                 c.number("tissue.lambda")));
}


/// Sliding symmetry u_x = 0 on x = 0: the x component of the displacement
/// (of the mixed space: src/model/mixed_space.hpp).
std::shared_ptr<const fem::DirichletBC<T>> symmetry_bc(const fem::FunctionSpace& W, bool mixed,
                                                       const TaggedDolfinxMesh& m)
{
  const auto facets = tagged_facets(*m.facets, generated::tag("symmetry"));
  if (mixed)
    return mixed_displacement_bc(W, facets, 0);
  auto Vx = W.sub({0});
  auto dofs = fem::locate_dofs_topological(*Vx, 2, facets);
  return std::make_shared<const fem::DirichletBC<T>>(T(0), std::move(dofs), Vx);
}

/// Newton from w = 0 to |R| <= 1e-11 |R(0)| (or round-off stagnation below
/// 1e-8 |R(0)|); the iterations, SolveError otherwise.
int solve_to_roundoff(ResidualNewton& newton, bool mixed, int refinements)
{
  const double r0 = newton.residual_norm();
  ResidualNewtonOptions no;
  no.rtol = 1e-11;
  no.max_iterations = 30;
  no.max_halvings = 12;
  no.step_rtol = 1e-13;
  no.accept_rtol = 1e-8;
  const auto nr = newton.solve(r0, no, [&](int it, double r) {
    spdlog::debug("incompressible MMS ({}) level {}: Newton {} |R|/|R0| = {:.3e}",
                  mixed ? "mixed" : "displacement", refinements, it, r / r0);
  });
  if (nr.lu_failed || !(nr.residual <= 1e-8 * r0))
    throw SolveError(fmt::format("incompressible MMS ({}) level {}: Newton did not converge "
                                 "(|R|/|R0| = {:.3e}{})", mixed ? "mixed" : "displacement",
                                 refinements, nr.residual / r0, nr.lu_failed ? ", LU failed" : ""));
  return nr.iterations;
}
/// Least-squares slope of ln e against ln h: sum (x - x_mean)(y - y_mean) /
/// sum (x - x_mean)^2 with x = ln h, y = ln e.
double log_log_slope(const std::vector<IncompressibleMmsLevel>& levels,
                     double IncompressibleMmsLevel::*error)
{
  double mx = 0, my = 0;
  for (const auto& L : levels)
  {
    mx += std::log(L.h_eff) / double(levels.size());
    my += std::log(L.*error) / double(levels.size());
  }
  double sxy = 0, sxx = 0;
  for (const auto& L : levels)
  {
    sxy += (std::log(L.h_eff) - mx) * (std::log(L.*error) - my);
    sxx += (std::log(L.h_eff) - mx) * (std::log(L.h_eff) - mx);
  }
  return sxy / sxx;
}
} // namespace

IncompressibleMmsLevel solve_incompressible_mms(const Config& c, bool mixed, int order,
                                                double mesh_size, int refinements, MPI_Comm comm,
                                                const IncompressibleMmsSetup& setup)
{
  check_request(c, mixed, order);
  Stopwatch stopwatch("incompressible MMS level");
  const IncompressibleForms uf = incompressible_forms(mixed, order);
  TaggedDolfinxMesh m = mms_level_mesh(c, order, mesh_size, refinements, comm, setup.meshes);
  auto W = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(uf.space, uf.coefficient, m.mesh));
  auto w = std::make_shared<fem::Function<T>>(W);
  MmsConstants all = mms_constants(c);
  all["mms_amplitude"] = std::make_shared<fem::Constant<T>>(setup.amplitude);
  all["mms_length"] = std::make_shared<fem::Constant<T>>(setup.length);
  all["mms_kappa"] = std::make_shared<fem::Constant<T>>(setup.kappa);
  const std::map<std::string, std::shared_ptr<const fem::Constant<T>>> constants(all.begin(), all.end());
  const std::map<std::string, std::shared_ptr<const fem::Function<T>>> coefficients{{uf.coefficient, w}};
  auto create = [&](ufcx_form* f, int rank)
  {
    std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces(rank, W);
    return std::make_shared<fem::Form<T>>(fem::create_form<T>(
        *f, spaces, coefficients, constants,
        {{fem::IntegralType::exterior_facet, m.facets.get()}}, m.mesh));
  };
  ResidualNewton newton(create(uf.residual, 1), create(uf.jacobian, 2), w, {symmetry_bc(*W, mixed, m)});

  IncompressibleMmsLevel L;
  L.refinements = refinements;
  L.newton_iterations = solve_to_roundoff(newton, mixed, refinements);
  auto scalar = [&](ufcx_form* f) { return mpi_sum(fem::assemble_scalar(*create(f, 0)), comm); };
  L.error_l2 = std::sqrt(scalar(uf.error_l2));
  L.error_h1 = std::sqrt(scalar(uf.error_h1));
  L.rel_l2 = L.error_l2 / std::sqrt(scalar(uf.norm_l2));
  L.rel_h1 = L.error_h1 / std::sqrt(scalar(uf.norm_h1));
  if (mixed)
  {
    L.error_p = std::sqrt(scalar(uf.error_p));
    L.rel_p = L.error_p / std::sqrt(scalar(uf.norm_p));
  }
  L.cells = m.mesh->topology().index_map(3)->size_global();
  L.dofs = W->dofmap()->index_map->size_global() * W->dofmap()->index_map_bs();
  L.seconds = stopwatch.seconds();
  return L;
}

IncompressibleMmsStudy incompressible_mms_study(const Config& c, bool mixed, int order,
                                                double mesh_size, int levels, MPI_Comm comm,
                                                const IncompressibleMmsSetup& setup)
{
  IncompressibleMmsStudy s;
  s.setup = setup;
  s.mixed = mixed;
  s.order = order;
  s.mesh_size = mesh_size;
  s.lambda_over_mu = c.number("tissue.lambda") / c.number("tissue.mu");
  const HalfCapSpec cap = HalfCapSpec::from(c);
  const double volume = M_PI * cap.H * (3 * cap.R * cap.R + cap.H * cap.H) / 12; // the half cap
  auto rate = [](double e0, double e1, double h0, double h1) { return std::log(e0 / e1) / std::log(h0 / h1); };
  for (int l = 0; l < levels; ++l)
  {
    s.levels.push_back(solve_incompressible_mms(c, mixed, order, mesh_size, l, comm, setup));
    auto& L = s.levels.back();
    L.h_eff = std::cbrt(volume / double(L.cells));
    spdlog::info("incompressible MMS ({} P{}) level {}: {} cells, {} dofs, L2 {:.4e}, H1 {:.4e}, "
                 "p {:.4e} ({} Newton, {:.1f} s)", mixed ? "mixed" : "displacement", order, l,
                 L.cells, L.dofs, L.error_l2, L.error_h1, L.error_p, L.newton_iterations, L.seconds);
    if (l == 0)
      continue;
    const auto& P = s.levels[l - 1];
    s.order_l2.push_back(rate(P.error_l2, L.error_l2, P.h_eff, L.h_eff));
    s.order_h1.push_back(rate(P.error_h1, L.error_h1, P.h_eff, L.h_eff));
    if (mixed)
      s.order_p.push_back(rate(P.error_p, L.error_p, P.h_eff, L.h_eff));
  }
  if (levels >= 2)
  {
    s.fit_l2 = log_log_slope(s.levels, &IncompressibleMmsLevel::error_l2);
    s.fit_h1 = log_log_slope(s.levels, &IncompressibleMmsLevel::error_h1);
    if (mixed)
      s.fit_p = log_log_slope(s.levels, &IncompressibleMmsLevel::error_p);
  }
  return s;
}

nlohmann::json to_json(const IncompressibleMmsStudy& s)
{
  nlohmann::json j;
  j["formulation"] = s.mixed ? "mixed" : "displacement";
  j["element_order"] = s.order;
  j["lambda_over_mu"] = s.lambda_over_mu;
  j["mesh_size"] = s.mesh_size;
  j["meshes"] = to_string(s.setup.meshes);
  j["solution"] = {{"amplitude_m", s.setup.amplitude}, {"length_m", s.setup.length},
                   {"kappa", s.setup.kappa}};
  j["expected_order_l2"] = s.order + 1;
  j["expected_order_h1"] = s.order;
  if (s.mixed)
    j["expected_order_p"] = s.order;
  for (const auto& L : s.levels)
    j["levels"].push_back({{"level", L.refinements}, {"cells", L.cells}, {"dofs", L.dofs},
                           {"h_eff", L.h_eff}, {"error_l2", L.error_l2}, {"error_h1", L.error_h1},
                           {"relative_error_l2", L.rel_l2}, {"relative_error_h1", L.rel_h1},
                           {"error_p", L.error_p}, {"relative_error_p", L.rel_p},
                           {"newton_iterations", L.newton_iterations}, {"seconds", L.seconds}});
  j["order_l2"] = s.order_l2;
  j["order_h1"] = s.order_h1;
  j["order_p"] = s.order_p;
  if (s.levels.size() >= 2)
  {
    j["fit_order_l2"] = s.fit_l2;
    j["fit_order_h1"] = s.fit_h1;
    if (s.mixed)
      j["fit_order_p"] = s.fit_p;
  }
  return j;
}

std::string mms_table(const IncompressibleMmsStudy& s)
{
  std::string out = fmt::format(
      "Incompressible MMS, {} P{}{} (lambda/mu = {:g}, {} meshes from {:g} m, u_ex = curl psi "
      "+ kappa (mu/lambda) grad phi, A = {:g} m, L = {:g} m, kappa = {:g}): expected L2 {}, H1 {}{}\n",
      s.mixed ? "mixed" : "displacement", s.order, s.mixed ? "-P1" : "", s.lambda_over_mu,
      to_string(s.setup.meshes), s.mesh_size, s.setup.amplitude, s.setup.length, s.setup.kappa,
      s.order + 1, s.order,
      s.mixed ? fmt::format(", p {}", s.order) : "");
  out += fmt::format("{:>5} {:>8} {:>8} {:>10} {:>11} {:>11} {:>11} {:>7} {:>7} {:>7}\n", "level",
                     "cells", "dofs", "h_eff[mm]", "u L2 rel", "u H1 rel", "p L2 rel", "p(uL2)",
                     "p(uH1)", "p(pL2)");
  for (std::size_t i = 0; i < s.levels.size(); ++i)
  {
    const auto& L = s.levels[i];
    auto o = [&](const std::vector<double>& v) { return i && i - 1 < v.size() ? fmt::format("{:.3f}", v[i - 1]) : "-"; };
    out += fmt::format("{:>5} {:>8} {:>8} {:>10.3f} {:>11.4e} {:>11.4e} {:>11} {:>7} {:>7} {:>7}\n",
                       L.refinements, L.cells, L.dofs, 1e3 * L.h_eff, L.rel_l2, L.rel_h1,
                       s.mixed ? fmt::format("{:.4e}", L.rel_p) : "-", o(s.order_l2), o(s.order_h1),
                       o(s.order_p));
  }
  if (s.levels.size() >= 2)
    out += fmt::format("least-squares slopes over levels 0-{}: u L2 {:.3f}, u H1 {:.3f}{}\n",
                       s.levels.size() - 1, s.fit_l2, s.fit_h1,
                       s.mixed ? fmt::format(", p L2 {:.3f}", s.fit_p) : "");
  return out;
}
} // namespace breastsim
