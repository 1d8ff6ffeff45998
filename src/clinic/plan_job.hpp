// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// `breastsim plan`: the patient model of each breast from its landmarks,
// then a goal-directed plan per breast (plan_search.hpp). With `symmetric`
// the second breast's post-op SN-N and N-IMF targets default to the first
// breast's result, and its resection leaves the same volume. Writes
// patient_model.json, plan.json, plan.txt, case_<side>.toml (the patient's
// case with the chosen incision) and <side>/ (its surgery in every posture
// of the case).
#include "output_target.hpp"
#include "patient_job.hpp"
#include "plan_search.hpp"

namespace breastsim::clinic
{
struct PatientPlan
{
  PatientModel patient;
  std::vector<SidePlan> sides;
  bool met() const;
};

/// InputError unless `base` solves standing first on the parametric cap,
/// some breast has a target, and every breast with targets has landmarks.
void check_plan_request(const Config& base, const Patient& p, const std::map<std::string, PlanTargets>& targets);

/// Collective. `targets`: per side ("left", "right"); sides of the patient
/// without targets are modelled but not planned unless `symmetric`.
/// Checked first by check_plan_request.
PatientPlan plan_patient(const Config& base, const Patient& p, double tolerance,
                         const std::map<std::string, PlanTargets>& targets, bool symmetric,
                         const OutputTarget& out, MPI_Comm comm);
/// Per side the plan in surgical terms, the model's incision and each target against the result.
std::string plan_table(const PatientPlan& p);
} // namespace breastsim::clinic
