// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim plan PATIENT.json --target [side.]key=value ... --out DIR`:
// goal-directed plans for a patient's breasts (src/clinic/plan_job.hpp).
#include "command.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "option_checks.hpp"
#include "overrides.hpp"
#include "plan_job.hpp"
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
  std::vector<std::string> sets, targets;
  double tolerance_mm = 1.0;
  bool symmetric = false;
  OutputOption out;
};

/// A length with its unit: "21cm", "210mm", "0.21m".
double length_value(const std::string& text, const std::string& option)
{
  for (const auto& [unit, scale] : {std::pair{"mm", 1e-3}, std::pair{"cm", 1e-2}, std::pair{"m", 1.0}})
  {
    const std::string u = unit;
    if (text.size() > u.size() && text.compare(text.size() - u.size(), u.size(), u) == 0)
    {
      try
      {
        std::size_t used = 0;
        const std::string number = text.substr(0, text.size() - u.size());
        const double v = std::stod(number, &used);
        if (used == number.size() && std::isfinite(v))
          return v * scale;
      }
      catch (const std::exception&)
      {
      }
    }
  }
  throw InputError(fmt::format("{} = '{}': a length with its unit, e.g. 21cm, 210mm or 0.21m", option, text));
}

double plain_value(const std::string& text, const std::string& option)
{
  try
  {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v))
      return v;
  }
  catch (const std::exception&)
  {
  }
  throw InputError(fmt::format("{} = '{}' is not a number", option, text));
}

/// `--target [left.|right.]key=value`: sn_n, n_imf (lengths), grams, lower_pole (a share in (0, 1)).
void add_target(std::map<std::string, clinic::PlanTargets>& all, std::set<std::string>& named_sides,
                const std::string& item)
{
  const auto eq = item.find('=');
  if (eq == std::string::npos)
    throw InputError(fmt::format("--target '{}': expected [left.|right.]key=value", item));
  std::string key = item.substr(0, eq);
  const std::string value = item.substr(eq + 1), option = "--target " + key;
  std::vector<std::string> sides = {"left", "right"};
  if (const auto dot = key.find('.'); dot != std::string::npos)
  {
    sides = {key.substr(0, dot)};
    key = key.substr(dot + 1);
    if (sides[0] != "left" && sides[0] != "right")
      throw InputError(fmt::format("{}: the side must be left or right", option));
    named_sides.insert(sides[0]);
  }
  double v = 0;
  if (key == "sn_n" || key == "n_imf")
  {
    v = length_value(value, option);
    const double lo = key == "sn_n" ? 0.15 : 0.03, hi = key == "sn_n" ? 0.45 : 0.25;
    check_range(v * 100, lo * 100, hi * 100, option, "cm");
  }
  else if (key == "grams")
  {
    v = plain_value(value.size() > 1 && value.back() == 'g' ? value.substr(0, value.size() - 1) : value, option);
    check_range(v, 10, 3000, option, "g");
  }
  else if (key == "lower_pole")
  {
    v = plain_value(value, option);
    check_range(v, 0.3, 0.8, option);
  }
  else
    throw InputError(fmt::format("{}: unknown target '{}' (allowed: sn_n, n_imf, grams, lower_pole)", option, key));
  for (const auto& side : sides)
  {
    auto& t = all[side];
    (key == "sn_n" ? t.sn_n : key == "n_imf" ? t.n_imf : key == "grams" ? t.grams : t.lower_pole) = v;
  }
}
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
              add_target(targets, named_sides, t);
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
