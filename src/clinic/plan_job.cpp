// SPDX-License-Identifier: LGPL-3.0-or-later
#include "plan_job.hpp"
#include "plan_drawing.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "on_root.hpp"
#include "output.hpp"
#include "posture.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim::clinic
{
bool PatientPlan::met() const
{
  return std::all_of(sides.begin(), sides.end(), [](const SidePlan& s) { return s.unmet.empty(); });
}

namespace
{
/// The exact volume of the neutral cap, full breast: pi H (3 R^2 + H^2) / 6.
double cap_volume(const Config& c)
{
  const double R = c.number("geometry.R"), H = c.number("geometry.H");
  return M_PI * H * (3 * R * R + H * H) / 6;
}

/// The second breast's targets for symmetry with the first's result: its
/// SN-N and N-IMF (unless given) and the weight that leaves the same volume.
PlanTargets symmetric_targets(PlanTargets t, const SidePlan& first, const SideModel& second)
{
  if (!t.sn_n)
    t.sn_n = first.best.sn_n;
  if (!t.n_imf)
    t.n_imf = first.best.n_imf;
  if (!t.grams)
    t.grams = 1e3 * second.config.number("tissue.rho") * (cap_volume(second.config) - first.best.volume_post);
  return t;
}

} // namespace

void check_plan_request(const Config& base, const Patient& p, const std::map<std::string, PlanTargets>& targets)
{
  const auto postures = requested_postures(base);
  if (postures.empty() || postures.front().theta_deg != 0.0)
    throw InputError("key 'postures.names': plans are judged standing, so the first posture must be standing "
                     "(theta = 0)");
  HalfCapSpec::from(base).require_parametric_cap("plan (the incision cuts the cap)");
  if (targets.empty() || std::all_of(targets.begin(), targets.end(), [](const auto& t) { return t.second.empty(); }))
    throw InputError("targets: no breast has a target (e.g. grams 400 and post-op SN-N 21 cm)");
  for (const auto& [side, t] : targets)
    if (!p.sides.count(side))
      throw InputError(fmt::format("targets of the {} breast: the patient has no landmarks of the {} breast", side,
                                   side));
}

PatientPlan plan_patient(const Config& base, const Patient& p, double tolerance,
                         const std::map<std::string, PlanTargets>& targets, bool symmetric,
                         const OutputTarget& out, MPI_Comm comm)
{
  check_plan_request(base, p, targets);
  OutputDir dir(out, comm);
  PatientPlan plan;
  plan.patient = fit_patient(base, p, tolerance, comm);
  std::vector<nlohmann::json> drawings;
  for (const auto& m : plan.patient.sides)
  {
    PlanTargets t = targets.count(m.side) ? targets.at(m.side) : PlanTargets{};
    if (symmetric && !plan.sides.empty())
      t = symmetric_targets(t, plan.sides.front(), m);
    if (t.empty())
      continue;
    log::info("plan: searching the {} breast's incision", m.side);
    const auto scratch = dir.path() / ("search-" + m.side);
    plan.sides.push_back(plan_side(m, t, scratch, dir.path() / m.side, comm));
    drawings.push_back(plan_drawing(m, plan.sides.back().best, dir.path() / m.side, comm));
    if (rank_of(comm) == 0)
      std::filesystem::remove_all(scratch); // the search's own surgery folder, inside this run's staging
    Config chosen = m.config;
    const auto& in = plan.sides.back().best.incision;
    chosen.set("incision.a_deg", in.a_deg);
    chosen.set("incision.s", in.s);
    chosen.set("incision.h", in.h);
    chosen.set("incision.d", in.d);
    write_text(dir.path() / ("case_" + m.side + ".toml"), chosen.to_toml(), comm);
  }
  nlohmann::json sides = nlohmann::json::array();
  for (std::size_t k = 0; k < plan.sides.size(); ++k)
  {
    sides.push_back(to_json(plan.sides[k]));
    sides.back()["drawing"] = drawings[k];
  }
  write_json(dir.path() / "patient_model.json", to_json(plan.patient), comm);
  write_json(dir.path() / "plan.json",
             {{"format", "breastsim-plan/1"}, {"id", p.id}, {"symmetric", symmetric}, {"met", plan.met()},
              {"sides", sides}},
             comm);
  write_text(dir.path() / "plan.txt", plan_table(plan), comm);
  dir.commit();
  return plan;
}

std::string plan_table(const PatientPlan& p)
{
  std::string t;
  for (const auto& s : p.sides)
  {
    const auto& b = s.best;
    t += fmt::format("{} breast: Wise (inverted-T) pattern\n", s.side);
    if (!b.ok)
    {
      t += "  no operable plan: " + b.error + "\n";
      continue;
    }
    const auto bsa = p.patient.body ? p.patient.body->surface_area() : std::nullopt;
    t += fmt::format("  marking (standing): new nipple at SN-N {:.1f} cm, vertical limb {:.1f} cm; "
                     "resection {:.0f} g{}\n",
                     100 * b.terms.new_nipple_sn_n, 100 * b.terms.vertical_limb, b.terms.resection_grams,
                     bsa ? fmt::format(" ({:.0f} g per m^2 of body surface)", b.terms.resection_grams / *bsa) : "");
    t += fmt::format("  model incision: a = {:.1f} deg, s = {:.1f} mm, h = {:.1f} mm, d = {:.1f} mm\n",
                     b.incision.a_deg, 1e3 * b.incision.s, 1e3 * b.incision.h, 1e3 * b.incision.d);
    auto row = [&](const char* name, double v, const std::optional<double>& target, double scale, const char* unit,
                   double tol)
    {
      const std::string goal = target ? fmt::format("target {:.1f} {}", scale * *target, unit) : "no target";
      const std::string ok = !target ? "" : std::abs(v - *target) <= tol ? "  met" : "  NOT met";
      t += fmt::format("  {:<24} {:>7.1f} {:<3} ({}){}\n", name, scale * v, unit, goal, ok);
    };
    row("post-op SN-N standing", b.sn_n, s.targets.sn_n, 100, "cm", s.targets.length_tolerance);
    row("post-op N-IMF standing", b.n_imf, s.targets.n_imf, 100, "cm", s.targets.length_tolerance);
    row("resection", b.terms.resection_grams, s.targets.grams, 1, "g",
        s.targets.grams ? s.targets.grams_tolerance * *s.targets.grams : 0);
    row("lower pole share", b.lower_pole, s.targets.lower_pole, 100, "%", s.targets.share_tolerance);
    for (const auto& line : s.trade_offs)
      t += "  trade-off: " + line + "\n";
    t += fmt::format("  searched {} plans\n", s.searched.size());
  }
  return t;
}
} // namespace breastsim::clinic
