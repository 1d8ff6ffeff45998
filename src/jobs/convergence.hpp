// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Mesh-convergence studies: a case solved on uniformly refined
// meshes (geometry.refinements = 0 .. N-1, refinement ratio r = 2), per
// quantity the observed order, the Richardson-extrapolated value and Roache's
// Grid Convergence Index of the finest level; optionally the MMS problem.
#include "config.hpp"
#include "mms.hpp"
#include "mms_mixed.hpp"
#include "output_target.hpp"
#include <filesystem>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim
{
/// Observed order, extrapolation and GCI from three levels q0 (coarse), q1,
/// q2 (fine) with refinement ratio r: p = ln(|q1-q0| / |q2-q1|) / ln r,
/// q_ext = q2 + (q2-q1)/(r^p - 1), GCI = Fs |(q2-q1)/q2| / (r^p - 1).
struct Richardson
{
  double order = 0, extrapolated = 0, gci = 0;
  bool monotone = true;  ///< q1-q0 and q2-q1 have the same sign
  bool valid = true;     ///< finite order (not already converged / stalled)
};
Richardson richardson(double q0, double q1, double q2, double r = 2.0, double Fs = 1.25);

struct QuantitySeries
{
  std::string name, unit;
  std::vector<double> values; ///< per level
  /// Observed order of each consecutive triple of levels (levels - 2 entries);
  /// the last one is also in `finest`.
  std::vector<double> orders;
  Richardson finest;          ///< from the three finest levels
};

struct ConvergenceStudy
{
  int element_order = 1;
  std::string posture;
  std::string refinement = "gmsh"; ///< "gmsh" (splitting) or "red"
  std::vector<int> refinements;
  std::vector<std::int64_t> cells, dofs;
  std::vector<double> seconds;
  std::vector<QuantitySeries> quantities;
};

/// What `converge` solves per level: the pre-operative standing posture, or
/// the surgery (incision, sutures, reset) and the post-operative standing
/// posture.
enum class ConvergeStage
{
  preop,
  surgery
};

/// How the levels are refined: gmsh's splitting (geometry.refinements), or
/// red refinement of the level-0 gmsh mesh with the new skin nodes moved onto
/// the cap (src/mesh/nested_mesh.hpp; preop stage only). gmsh's splitting does
/// not halve the longest edge at the first split and lowers the smallest
/// dihedral angle (docs/CONVERGENCE.md).
enum class ConvergeRefinement
{
  gmsh,
  red
};

/// Quantities `converge` knows: the observables of the solved posture, and
/// with the surgery stage also resected_volume and max_gap (suture).
std::vector<std::string> convergence_quantities();

/// Solve the case's standing posture (pre-operative, or post-operative after
/// the case's surgery) on `levels` refinements for each element order.
/// Collective. Throws InputError on an unknown quantity, levels outside 3..5,
/// or a surgery quantity without the surgery stage.
std::vector<ConvergenceStudy> converge_case(const Config& c, int levels,
                                            const std::vector<int>& orders,
                                            const std::vector<std::string>& quantities,
                                            MPI_Comm comm, ConvergeStage stage = ConvergeStage::preop,
                                            ConvergeRefinement refine = ConvergeRefinement::gmsh);

nlohmann::json to_json(const ConvergenceStudy& s);
std::string convergence_table(const ConvergenceStudy& s);

/// Log-log plot(s) of the JSON written by `converge` (python3 + matplotlib):
/// |q - q_ext| (or the MMS errors) against the mesh level. Returns false (and
/// leaves no PNG) if python3/matplotlib fail.
bool plot_convergence(const std::filesystem::path& json, const std::filesystem::path& png);
/// What `converge` is asked for.
struct ConvergeRequest
{
  int levels = 3;
  std::vector<int> orders{1};
  std::vector<std::string> quantities;
  bool mms = false; ///< the manufactured-solution problem instead of the case's posture
  MmsMeshes mms_meshes = MmsMeshes::nested;
  /// The nearly incompressible MMS's u_ex (tissue.formulation = mixed); its
  /// mesh family is mms_meshes.
  IncompressibleMmsSetup mms_incompressible;
  ConvergeStage stage = ConvergeStage::preop;
  ConvergeRefinement refine = ConvergeRefinement::gmsh;
};

/// Element orders from a list like "1,2"; InputError naming --order otherwise.
std::vector<int> parse_orders(const std::string& text);

struct ConvergeReport
{
  std::string table;    ///< the studies' tables, as printed
  bool plotted = false; ///< convergence.png written (python3 + matplotlib worked)
};

/// The `converge` job: run the studies and write convergence.json,
/// convergence.txt and convergence.png into `out` (replaced only on success).
ConvergeReport run_convergence(const Config& c, const ConvergeRequest& r, const OutputTarget& out,
                               MPI_Comm comm);
} // namespace breastsim
