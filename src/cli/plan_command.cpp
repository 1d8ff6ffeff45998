// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim plan PATIENT.json --target [side.]key=value ... --out DIR`:
// goal-directed plans for a patient's breasts (src/clinic/plan_job.hpp).
#include "command.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "option_checks.hpp"
#include "overrides.hpp"
#include "plan_job.hpp"
#include "plan_targets.hpp"
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <set>

namespace breastsim::cli
{
namespace
{
struct PlanOptions
{
  std::string patient_file, case_file;
  std::vector<std::string> sets, targets, incisions;
  double tolerance_mm = 1.0;
  bool symmetric = false;
  OutputOption out;
};

} // namespace

Command add_plan_command(CLI::App& root)
{
  auto o = std::make_shared<PlanOptions>();
  auto* app = root.add_subcommand("plan", "goal-directed reduction plans: post-op targets in, the incision that "
                                          "meets them out (docs/CLINIC.md)");
  app->add_option("patient", o->patient_file, "patient file (breastsim-patient/1 JSON)")->required();
  app->add_option("--target", o->targets,
                  "[left.|right.]key=value: sn_n=21cm, n_imf=7cm (post-op standing), grams=400 (resection), "
                  "lower_pole=0.55 (repeatable; without a side, for both)")
      ->allow_extra_args(false);
  app->add_option("--incision", o->incisions,
                  "[left.|right.]a_deg,s,h,d (deg, m): evaluate this incision in surgical terms, no search (expert)")
      ->allow_extra_args(false);
  app->add_flag("--symmetric", o->symmetric,
                "the second breast aims at the first's post-op SN-N, N-IMF and volume");
  app->add_option("--case", o->case_file, "case file for the material, mesh and solver (default: every default)");
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  app->add_option("--tolerance", o->tolerance_mm, "largest landmark error of the patient model [mm], in [0.1, 10]")
      ->capture_default_str();
  add_output_option(app, o->out, "output folder (default results/plan); replaced on success");
  return {app, [o]()
          {
            check_range(o->tolerance_mm, 0.1, 10, "--tolerance", "mm");
            std::map<std::string, clinic::PlanTargets> targets;
            std::set<std::string> named_sides; // sides a target names; the others' targets apply where there are landmarks
            for (const auto& t : o->targets)
              clinic::add_target_text(targets, named_sides, t);
            for (const auto& i : o->incisions)
              clinic::add_incision_text(targets, named_sides, i);
            const clinic::Patient p = clinic::read_patient(o->patient_file);
            for (auto it = targets.begin(); it != targets.end();)
              it = p.sides.count(it->first) || named_sides.count(it->first) ? std::next(it) : targets.erase(it);
            const Config c = load_case(o->case_file, o->sets);
            std::vector<std::string> inputs{o->patient_file};
            if (!o->case_file.empty())
              inputs.push_back(o->case_file);
            const auto out = claim_output(o->out, "results/plan", inputs);
            const clinic::PatientPlan plan =
                clinic::plan_patient(c, p, 1e-3 * o->tolerance_mm, targets, o->symmetric, out, MPI_COMM_WORLD);
            if (log::is_root())
            {
              std::cout << clinic::patient_table(plan.patient) << clinic::plan_table(plan) << "results written to "
                        << out.path().string() << "/ (plan.json, plan.txt, case_<side>.toml, <side>/)\n";
              for (const auto& s : plan.sides)
                for (const auto& u : s.unmet)
                  std::cerr << "breastsim: target not met, " << s.side << " breast: " << u << "\n";
            }
            return plan.met() ? 0 : 4;
          }};
}
} // namespace breastsim::cli
