// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Manufactured solution for nearly incompressible tissue
// (verification/forms/mms_mixed.py): the tissue of eq. (5) with the base
// springs, a divergence-free u_ex (and p_ex = lambda (J(u_ex) - 1)), solved
// with the displacement formulation (P1 or P2) or the mixed Taylor-Hood
// P2-P1 formulation (tissue.formulation = mixed) on the nested red-refined
// half cap. Expected orders: displacement Pp L2 p + 1, H1 p (reached only
// once h resolves the locking); mixed P2-P1 u L2 3, H1 2, p L2 2 uniformly
// in lambda / mu.
#include "config.hpp"
#include "mms.hpp"
#include <cstdint>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim
{
/// The manufactured field u_ex = curl psi + kappa (mu / lambda) grad phi
/// (verification/forms/mms_mixed.py) and the mesh family: amplitude A and
/// length scale L (|u_ex| ~ A, |grad u_ex| ~ A / L), the pressure p_ex =
/// lambda (J - 1) ~ kappa mu A / L (linear in A) + lambda (A / L)^2 (the
/// quadratic part of J, of length scale L / 2). The defaults reach the
/// asymptotic orders on the 16 mm cap; where p_ex dominates the stress at a
/// short length scale (e.g. kappa = 0, A = 3e-4 m, L = 0.08 m) the velocity
/// error converges faster than theory on these meshes (docs/VERIFICATION.md).
struct IncompressibleMmsSetup
{
  double amplitude = 6e-5; ///< A [m]
  double length = 0.16;    ///< L [m]
  double kappa = 1;        ///< weight of the volumetric part of u_ex
  MmsMeshes meshes = MmsMeshes::nested;
};

struct IncompressibleMmsLevel
{
  int refinements = 0;
  std::int64_t cells = 0, dofs = 0;
  double h_eff = 0;                   ///< (cap volume / cells)^(1/3) [m]
  double error_l2 = 0, error_h1 = 0;  ///< ||u_h - u_ex||_L2, |u_h - u_ex|_H1
  double rel_l2 = 0, rel_h1 = 0;      ///< relative to ||u_ex||_L2, |u_ex|_H1
  double error_p = 0, rel_p = 0;      ///< ||p_h - p_ex||_L2 [Pa m^(3/2)] and relative (mixed only)
  int newton_iterations = 0;
  double seconds = 0;
};

struct IncompressibleMmsStudy
{
  bool mixed = false;
  int order = 2;                ///< displacement degree (mixed: 2, pressure 1)
  double lambda_over_mu = 0;
  double mesh_size = 0;
  IncompressibleMmsSetup setup;
  std::vector<IncompressibleMmsLevel> levels;
  std::vector<double> order_l2, order_h1, order_p; ///< between consecutive levels
  /// Least-squares slopes of ln e against ln h_eff over all levels (>= 2).
  double fit_l2 = 0, fit_h1 = 0, fit_p = 0;
};

/// One level: the case's tissue.mu, tissue.lambda and base springs
/// (registry defaults otherwise), the setup's solution and mesh family. mixed needs order 2
/// and tissue.lambda > 0 (InputError naming the key otherwise). Collective.
IncompressibleMmsLevel solve_incompressible_mms(const Config& c, bool mixed, int order,
                                                double mesh_size, int refinements, MPI_Comm comm,
                                                const IncompressibleMmsSetup& setup = {});

/// Levels 0 .. levels-1, the observed orders log(e_i/e_i+1)/log(h_i/h_i+1)
/// and the least-squares slopes over all levels.
IncompressibleMmsStudy incompressible_mms_study(const Config& c, bool mixed, int order,
                                                double mesh_size, int levels, MPI_Comm comm,
                                                const IncompressibleMmsSetup& setup = {});

nlohmann::json to_json(const IncompressibleMmsStudy& s);
std::string mms_table(const IncompressibleMmsStudy& s);
} // namespace breastsim
