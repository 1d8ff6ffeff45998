// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Goal-directed planning (docs/CLINIC.md, "Goal-directed plans"): the
// surgeon states post-operative targets for one breast - SN-N and N-IMF
// standing, the resection's weight, the lower pole's share - and the search
// finds the incision that meets them. The weight fixes the keel's angle a
// (angle_for_grams, geometry only); the new nipple's height s and D's
// height h are searched, each evaluation one surgery solved standing: a
// grid over (s, h), then NLopt's Nelder-Mead from its best point, then
// also in the new fold's depth d when two or more targets besides the
// weight are set and still missed.
#include "patient_fit.hpp"
#include "surgical_terms.hpp"
#include <filesystem>
#include <optional>

namespace breastsim::clinic
{
struct PlanTargets
{
  std::optional<double> sn_n, n_imf;   ///< post-op standing [m]
  std::optional<double> grams;         ///< the resection's weight, this breast [g]
  std::optional<double> lower_pole;    ///< post-op lower pole's share of the volume
  double length_tolerance = 5e-3;      ///< [m]
  double grams_tolerance = 0.05;       ///< relative
  double share_tolerance = 0.03;
  /// The surgeon's own incision in the model's terms (the expert view):
  /// evaluated as it is, not searched; the targets, if any, are compared.
  std::optional<IncisionSpec> incision;
  bool empty() const { return !sn_n && !n_imf && !grams && !lower_pole && !incision; }
};

/// One evaluated plan: the incision, its surgical terms and the post-op standing breast.
struct PlanOutcome
{
  IncisionSpec incision;
  SurgicalTerms terms;
  bool ok = false;
  std::string error;             ///< why the plan was not operated
  double sn_n = 0, n_imf = 0;    ///< post-op standing [m]
  double lower_pole = 0;         ///< post-op lower pole's share (pole_volumes.hpp)
  double volume_post = 0;        ///< post-op neutral volume, full breast [m^3]
  Point nipple{};                ///< post-op standing [m]
  double objective = 0;          ///< sum of ((value - target) / tolerance)^2
};

struct SidePlan
{
  std::string side;
  PlanTargets targets;
  PlanOutcome best;
  std::vector<PlanOutcome> searched;
  std::vector<std::string> unmet; ///< each target missed: the target and how close it came
  std::vector<std::string> trade_offs; ///< when targets conflict: how close each comes alone
};

/// Collective. Search the plan of one patient breast `m` for `t`; each
/// evaluation's surgery is written to `scratch` (a folder this run owns).
/// The best plan's surgery is then run with the case's postures into
/// `final_dir`.
SidePlan plan_side(const SideModel& m, const PlanTargets& t, const std::filesystem::path& scratch,
                   const std::filesystem::path& final_dir, MPI_Comm comm);
/// Evaluate one incision on patient breast `m` (collective): the surgery
/// into `dir`, measured standing.
PlanOutcome evaluate_plan(const SideModel& m, const IncisionSpec& in, const Config& c,
                          const std::filesystem::path& dir, MPI_Comm comm);
double plan_objective(const PlanOutcome& o, const PlanTargets& t);
/// The targets `o` misses, each with the target and the value reached.
std::vector<std::string> unmet_targets(const PlanOutcome& o, const PlanTargets& t);
/// For each length or share target, the searched plan that comes closest
/// to it alone and what the other targets are there.
std::vector<std::string> trade_offs(const std::vector<PlanOutcome>& searched, const PlanTargets& t);
nlohmann::json to_json(const SidePlan& p);
} // namespace breastsim::clinic
