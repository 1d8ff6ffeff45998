// SPDX-License-Identifier: LGPL-3.0-or-later
// The diagnosis as JSON and as plain words (diagnosis_report.hpp).
#include "diagnosis_report.hpp"
#include "evidence.hpp"
#include "field_discovery.hpp"
#include "law_discovery.hpp"
#include "candidates.hpp"
#include "separation.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

namespace breastsim::diagnosis
{
namespace
{
nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); }

/// Rivals as a JSON array (diagnosis.json: undecided[].rivals, rounds[].rivals).
nlohmann::json rivals_json(const std::vector<Rival>& rivals)
{
  nlohmann::json a = nlohmann::json::array();
  for (const auto& x : rivals)
    a.push_back({{"candidate", x.candidate}, {"z", x.z}, {"margin_difference", x.margin_diff}});
  return a;
}

/// v[i], 0 where v has no entry i.
double at(const std::vector<double>& v, std::size_t i) { return i < v.size() ? v[i] : 0.0; }

nlohmann::json to_json(const FitState& s, const Recording& rec)
{
  nlohmann::json j;
  j["parameters"] = nlohmann::json::array();
  for (std::size_t i = 0; i < s.names.size(); ++i)
  {
    nlohmann::json p = {{"name", s.names[i]}, {"unit", s.units[i]}, {"value", s.values[i]}};
    if (i < s.uncertainty.interval.size())
    {
      p["interval95"] = {number_or_null(s.uncertainty.interval[i][0]),
                         number_or_null(s.uncertainty.interval[i][1])};
      p["se_log"] = number_or_null(s.uncertainty.se_log[i]);
      p["flag"] = s.uncertainty.flags[i];
    }
    j["parameters"].push_back(p);
  }
  j["chi2"] = s.chi2;
  j["dof"] = s.dof;
  j["reduced_chi2"] = s.chi2 / std::max(s.dof, 1);
  j["gof_z"] = s.gof_z;
  j["gof_p"] = s.gof_p;
  j["evaluations"] = s.evaluations;
  j["postures"] = nlohmann::json::array();
  for (std::size_t p = 0; p < rec.postures.size(); ++p)
  {
    nlohmann::json q = {{"name", rec.postures[p].name},
                        {"rms_mm", 1e3 * s.rms[p]},
                        {"max_mm", 1e3 * s.max_abs[p]}};
    if (std::isfinite(s.nipple_error[p][0]))
      q["nipple_error_mm"] = {1e3 * s.nipple_error[p][0], 1e3 * s.nipple_error[p][1],
                              1e3 * s.nipple_error[p][2]};
    j["postures"].push_back(q);
  }
  return j;
}

bool unsolved_on_finer(const Diagnosis& d, const std::string& posture)
{
  return std::find(d.unsolved_on_finer.begin(), d.unsolved_on_finer.end(), posture)
         != d.unsolved_on_finer.end();
}

std::string fit_line(const FitState& s)
{
  std::string p;
  for (std::size_t i = 0; i < s.names.size(); ++i)
  {
    p += fmt::format("{}{} = {:.4g} {}", i ? ", " : "", s.names[i], s.values[i], s.units[i]);
    if (i < s.uncertainty.interval.size())
      p += fmt::format(" [{:.4g}, {:.4g}]", s.uncertainty.interval[i][0], s.uncertainty.interval[i][1]);
  }
  return p.empty() ? "(no free parameter)" : p;
}

/// Steps WHAT and MODEL IT of one round, with the evidence for and against
/// each refitted candidate.
std::string candidates_text(const Round& r, const Recording& rec)
{
  std::string s;
  s += "  WHAT: candidate scores (Lagrange multiplier, one-sided; mesh-error allowance):\n";
  for (const auto& c : r.scores)
    s += fmt::format("    {:<20} S = {:9.1f}   p = {:.2g}   allowance {:.1f}\n", c.name, c.score,
                     c.p_value, c.mesh_allowance);
  for (const auto& c : r.scores)
    if (std::find(r.screened_out.begin(), r.screened_out.end(), c.name) != r.screened_out.end())
      s += fmt::format("  {}: not refitted: its score {:.1f} is below {:g} x its critical value {:.1f} "
                       "({:.1f} + mesh allowance {:.1f}); its refit could not pass\n",
                       c.name, c.score, r.screen_fraction, r.critical + c.mesh_allowance, r.critical,
                       c.mesh_allowance);
  if (r.tested.empty())
    s += r.screened_out.empty() ? "  no candidate is significant\n" : "  no candidate is refitted\n";
  else
  {
    std::string refits;
    for (const auto& [name, lr] : r.refits)
      refits += fmt::format("{}{} LR = {:.1f}", refits.empty() ? "" : ", ", name, lr);
    std::string runner = "(none)";
    for (const auto& c : r.scores)
      if (c.name != r.tested)
      {
        runner = c.name;
        break;
      }
    s += fmt::format("  best: {} (runner-up: {}; refitted: {})\n", r.tested, runner, refits);
    s += fmt::format("  MODEL IT: refit with {}: {}\n", r.tested, fit_line(r.after));
    s += fmt::format("  likelihood ratio {:.1f} against the critical value {:.1f} ({:.1f} + mesh "
                     "allowance {:.1f}): {}\n",
                     r.lr, r.critical_used, r.critical, r.critical_used - r.critical,
                     r.accepted ? "ACCEPTED" : "rejected");
    for (const auto& x : r.rivals)
      s += fmt::format("  SEPARATION: {} fits about as well as {}: margin difference {:.1f}, Vuong "
                       "z = {:.2f}, below the separation level; {} is named only if {} is found too\n",
                       x.candidate, r.tested, x.margin_diff, x.z, r.tested, x.candidate);
    if (r.accepted)
    {
      s += "  FIT BEFORE -> AFTER:\n";
      for (std::size_t p = 0; p < rec.postures.size(); ++p)
        s += fmt::format("    {:<12} RMS {:.3f} -> {:.3f} mm, max {:.3f} -> {:.3f} mm\n",
                         rec.postures[p].name, 1e3 * r.before.rms[p], 1e3 * r.after.rms[p],
                         1e3 * r.before.max_abs[p], 1e3 * r.after.max_abs[p]);
    }
  }
  if (!r.evidence.empty())
  {
    s += "  EVIDENCE (each refitted candidate, the rules of the decision):\n";
    for (const auto& e : r.evidence)
      s += evidence_text(e);
  }
  return s;
}

/// Candidates whose LR passed but which other rules refused, with the reasons.
std::string refused_text(const Diagnosis& d)
{
  std::string t;
  for (const auto& r : d.rounds)
    for (const auto& e : r.evidence)
      if (e.lr > e.critical && !e.failed.empty())
        t += fmt::format(" {} was refused although its LR {:.1f} passes {:.1f}: {}.", e.candidate,
                         e.lr, e.critical, e.failed.back());
  return t;
}

/// The named terms whose form the data cannot tell from another form of
/// the same physics (separation.hpp).
std::string form_text(const Diagnosis& d)
{
  std::string t;
  for (const auto& r : d.rounds)
  {
    if (!r.accepted || std::find(d.discovered.begin(), d.discovered.end(), r.tested) == d.discovered.end())
      continue;
    for (const auto& x : same_physics_rivals(r))
      t += fmt::format(" The physics {} is named, but its form is not decided: {} and {} fit "
                       "alike (z = {:.2f}); the fit carries {}, the larger margin.",
                       candidate(r.tested).family, r.tested, x.candidate, x.z, r.tested);
  }
  return t;
}

/// The terms the fit carries but the data cannot name (separation.hpp).
std::string undecided_text(const Diagnosis& d)
{
  std::string t;
  for (const auto& u : d.undecided)
  {
    std::string rivals;
    for (const auto& x : u.rivals)
      rivals += fmt::format("{}{} (z = {:.2f})", rivals.empty() ? "" : ", ", x.candidate, x.z);
    t += fmt::format(" The data need a term but cannot tell {} from {}: the missing physics lies "
                     "between these forms and neither is named (case.diagnosed.toml carries {}, "
                     "the larger margin, to reproduce the shape).",
                     u.used, rivals, u.used);
  }
  return t;
}
} // namespace

std::string verdict_text(const Diagnosis& d, const Recording& rec, double alpha)
{
  const FitState& first = d.rounds.front().before;
  const FitState& last = d.final_fit;
  const double noise_mm = 1e3 * rec.noise_sigma;
  auto rms_all = [](const FitState& s)
  {
    double ss = 0;
    std::size_t n = 0;
    for (const auto& v : s.distances)
      for (double x : v)
      {
        ss += x * x;
        ++n;
      }
    return 1e3 * std::sqrt(ss / std::max<std::size_t>(n, 1));
  };
  if (d.fit_only)
    return fmt::format("Surface fit of the model: RMS distance {:.3f} mm against the noise {:.3f} mm "
                       "(chi2/dof = {:.3f}, p = {:.2g}: {}).",
                       rms_all(first), noise_mm, first.chi2 / first.dof, first.gof_p,
                       first.gof_p > alpha ? "at the noise level"
                                           : "systematic misfit; `breastsim diagnose` looks for "
                                             "the missing physics");
  if (d.discovered.empty() && !d.undecided.empty())
    return fmt::format("No term is named. RMS distance {:.3f} -> {:.3f} mm (noise {:.3f} mm).{}{}",
                       rms_all(first), rms_all(last), noise_mm, undecided_text(d), refused_text(d));
  if (d.discovered.empty())
  {
    if (first.gof_p > alpha)
      return fmt::format("The current model explains the recording: RMS distance {:.3f} mm against "
                         "the noise {:.3f} mm (chi2/dof = {:.3f}, p = {:.2g}); no candidate physics "
                         "is significant at {:g}. No term was added (case.diagnosed.toml: the "
                         "current model, refitted).{}",
                         rms_all(first), noise_mm, first.chi2 / first.dof, first.gof_p, alpha,
                         refused_text(d));
    return fmt::format("The residual is systematic (RMS {:.3f} mm against the noise {:.3f} mm, "
                       "chi2/dof = {:.3f}, p = {:.2g}) but no candidate of the library explains it "
                       "significantly: the missing physics is outside the library, or a known "
                       "parameter is wrong. No term was added.{}",
                       rms_all(first), noise_mm, first.chi2 / first.dof, first.gof_p,
                       refused_text(d));
  }
  std::string what;
  for (const auto& name : d.discovered)
  {
    const Candidate& c = candidate(name);
    const std::size_t i = std::find(last.names.begin(), last.names.end(), c.parameter) - last.names.begin();
    const std::string form = c.family == name      ? ""
                             : !c.extends.empty() ? fmt::format(", a regional variation of {}", c.extends)
                                                  : fmt::format(", a form of {}", c.family);
    what += fmt::format("{}{} ({}{}): {} = {:.4g} {} (95 % interval [{:.4g}, {:.4g}])",
                        what.empty() ? "" : "; ", name, c.physics, form, c.parameter, last.values[i],
                        c.unit, last.uncertainty.interval[i][0], last.uncertainty.interval[i][1]);
  }
  const std::string rest
      = last.gof_p > alpha
            ? fmt::format("the remaining residual is at the noise level (chi2/dof = {:.3f}, p = {:.2g}).",
                          last.chi2 / last.dof, last.gof_p)
            : fmt::format("the remaining residual is still above the noise level (chi2/dof = {:.3f}, "
                          "p = {:.2g}): more is missing than the library explains.",
                          last.chi2 / last.dof, last.gof_p);
  return fmt::format("Missing physics found: {}. RMS distance {:.3f} -> {:.3f} mm (noise {:.3f} mm); {}{}{}{}",
                     what, rms_all(first), rms_all(last), noise_mm, rest, form_text(d),
                     undecided_text(d), refused_text(d));
}

namespace
{
/// ", per point up to ..." of a local noise floor.
std::string local_floor_text(const Diagnosis& d, std::size_t p, double sigma)
{
  if (p >= d.local_floor_max.size())
    return "";
  const double e = d.local_floor_max[p];
  return fmt::format(" (RMS); per point up to {:.3f} mm -> {:.3f} mm", 1e3 * e,
                     1e3 * std::hypot(sigma, e));
}
} // namespace

nlohmann::json noise_floor_json(const Diagnosis& d, const Recording& rec)
{
  auto a = nlohmann::json::array();
  for (std::size_t p = 0; p < d.mesh_error.size(); ++p)
  {
    nlohmann::json f = {{"posture", rec.postures[p].name},
                        {"mesh_error_mm", 1e3 * d.mesh_error[p]},
                        {"sigma_eff_mm", 1e3 * d.sigma_eff[p]},
                        {"local_mesh_error_max_mm", nullptr}}; // null: no noise floor
    if (p < d.local_floor_max.size())
      f["local_mesh_error_max_mm"] = 1e3 * d.local_floor_max[p];
    a.push_back(f);
  }
  return a;
}

nlohmann::json to_json(const Diagnosis& d, const Recording& rec)
{
  nlohmann::json j;
  j["format"] = "breastsim-diagnosis/1";
  j["noise_sigma_mm"] = 1e3 * d.noise_sigma;
  j["noise_floor"] = noise_floor_json(d, rec);
  j["unsolved_on_finer_mesh"] = d.unsolved_on_finer;
  j["lost_on_finer_mesh"] = d.lost_on_finer;
  j["rejoined_on_finer_mesh"] = d.rejoined_on_finer;
  j["final_values_from_finer_mesh"] = d.final_on_finer_mesh;
  j["verdict"] = d.verdict;
  j["discovered"] = d.discovered;
  j["discovered_physics"] = physics_of(d.discovered);
  j["discovered_forms"] = nlohmann::json::array();
  for (const auto& name : d.discovered)
    j["discovered_forms"].push_back(
        {{"term", name}, {"physics", candidate(name).family}, {"parameter", candidate(name).parameter},
         {"extends", candidate(name).extends}});
  j["undecided"] = nlohmann::json::array();
  for (const auto& u : d.undecided)
  {
    j["undecided"].push_back({{"used", u.used}, {"rivals", rivals_json(u.rivals)}});
  }
  j["diagnosis_mesh"] = {{"order", d.order}, {"mesh_size_m", d.mesh_size}, {"mesh_ratio", d.mesh_ratio}};
  j["rounds"] = nlohmann::json::array();
  for (const auto& r : d.rounds)
  {
    nlohmann::json q;
    q["fit"] = to_json(r.before, rec);
    q["regions"] = nlohmann::json::array();
    for (const auto& g : r.regions)
      q["regions"].push_back({{"posture", g.posture},
                              {"where", g.where},
                              {"points", g.points},
                              {"centroid_mm", {1e3 * g.centroid[0], 1e3 * g.centroid[1], 1e3 * g.centroid[2]}},
                              {"mean_residual_mm", 1e3 * g.mean_residual},
                              {"max_residual_mm", 1e3 * g.max_residual},
                              {"z", g.z}});
    q["scores"] = nlohmann::json::array();
    for (const auto& s : r.scores)
      q["scores"].push_back({{"candidate", s.name},
                             {"score", s.score},
                             {"p_value", s.p_value},
                             {"linearised_estimate", s.estimate},
                             {"mesh_allowance", s.mesh_allowance}});
    q["screened_out"] = r.screened_out;
    if (!r.tested.empty())
    {
      q["tested"] = r.tested;
      q["refits"] = nlohmann::json::array();
      for (const auto& [name, lr] : r.refits)
        q["refits"].push_back({{"candidate", name}, {"likelihood_ratio", lr}});
      q["refit"] = to_json(r.after, rec);
      q["likelihood_ratio"] = r.lr;
      q["critical_value"] = r.critical_used;
      q["critical_value_noise_only"] = r.critical;
      q["accepted"] = r.accepted;
      q["evidence"] = nlohmann::json::array();
      for (const auto& e : r.evidence)
        q["evidence"].push_back(to_json(e));
      q["rivals"] = rivals_json(r.rivals);
    }
    j["rounds"].push_back(q);
  }
  if (d.field)
    j["field"] = to_json(*d.field);
  if (d.law)
    j["law"] = to_json(*d.law);
  j["final"] = to_json(d.final_fit, rec);
  j["se_log_numerical"] = d.se_numerical;
  j["se_log_statistical"] = d.se_statistical;
  j["se_log_model_form"] = d.se_model_form;
  j["se_log_posture_jackknife"] = d.se_posture_jackknife;
  j["se_log_patch_jackknife"] = d.se_patch_jackknife;
  j["posture_solves"] = d.posture_solves;
  j["wall_time_s"] = d.seconds;
  return j;
}

std::string report_text(const Diagnosis& d, const Recording& rec)
{
  std::string s;
  int n = 0;
  for (const auto& p : rec.postures)
    n += static_cast<int>(p.points.size());
  s += fmt::format("Diagnosis of {} recorded points in {} postures (noise {:.3f} mm)\n", n,
                   rec.postures.size(), 1e3 * d.noise_sigma);
  if (d.mesh_size > 0)
    s += fmt::format("  diagnosis mesh: P{} at {:.1f} mm{}\n", d.order, 1e3 * d.mesh_size,
                     d.mesh_ratio > 1 ? fmt::format(", check mesh {:.1f} mm", 1e3 * d.mesh_size / d.mesh_ratio)
                                      : std::string());
  for (std::size_t p = 0; p < d.mesh_error.size(); ++p)
    if (d.mesh_error[p] > 0)
      s += fmt::format("  numerical noise floor {:<12} mesh error {:.3f} mm -> sigma_eff {:.3f} mm{}{}\n",
                       rec.postures[p].name, 1e3 * d.mesh_error[p], 1e3 * d.sigma_eff[p],
                       local_floor_text(d, p, d.noise_sigma),
                       unsolved_on_finer(d, rec.postures[p].name) ? " (not solved on the finer mesh: "
                                                                    "the largest of the others')"
                                                                  : "");
  if (!d.unsolved_on_finer.empty())
    s += fmt::format("  the fitted current model cannot be solved on the finer mesh in {}: the "
                     "refinement checks compare the LR of the other postures\n",
                     fmt::join(d.unsolved_on_finer, ", "));
  if (!d.lost_on_finer.empty())
    s += fmt::format("  a later model of this diagnosis cannot be solved on the finer mesh in {}: "
                     "left out of the finer mesh's solves from then on (the step that met it was "
                     "repeated without it)\n",
                     fmt::join(d.lost_on_finer, ", "));
  if (!d.rejoined_on_finer.empty())
    s += fmt::format("  solved on the finer mesh again once a term was found, and back in its "
                     "checks: {}\n",
                     fmt::join(d.rejoined_on_finer, ", "));
  for (std::size_t k = 0; k < d.rounds.size(); ++k)
  {
    const Round& r = d.rounds[k];
    s += fmt::format("\nRound {}: current model fitted: {}\n", k + 1, fit_line(r.before));
    s += fmt::format("  goodness of fit: chi2/dof = {:.3f} ({} dof), z = {:.1f}, p = {:.2g}\n",
                     r.before.chi2 / r.before.dof, r.before.dof, r.before.gof_z, r.before.gof_p);
    for (std::size_t p = 0; p < rec.postures.size(); ++p)
      s += fmt::format("  {:<12} RMS {:.3f} mm, max {:.3f} mm\n", rec.postures[p].name,
                       1e3 * r.before.rms[p], 1e3 * r.before.max_abs[p]);
    s += "  WHERE: ";
    if (r.regions.empty())
      s += "no region of systematic residual\n";
    else
    {
      s += fmt::format("{} region(s) of systematic residual\n", r.regions.size());
      for (std::size_t g = 0; g < std::min<std::size_t>(r.regions.size(), 6); ++g)
      {
        const Region& x = r.regions[g];
        s += fmt::format("    {:<12} {}: {} points, recording {} the model by {:.2f} mm on average "
                         "(max {:.2f} mm), z = {:.1f}\n",
                         x.posture, x.where, x.points, x.mean_residual > 0 ? "outside" : "inside",
                         1e3 * std::abs(x.mean_residual), 1e3 * x.max_residual, x.z);
      }
    }
    if (d.fit_only)
      continue;
    s += candidates_text(r, rec);
  }
  if (d.field)
    s += field_text(*d.field, rec);
  if (d.law)
    s += law_text(*d.law, rec);
  if (!d.se_numerical.empty())
    s += fmt::format("\nFinal fit on the {} (numerical{} uncertainty included): {}\n",
                     d.final_on_finer_mesh ? "finer check mesh"
                                           : "diagnosis mesh (a posture is left out of the finer one)",
                     d.se_model_form.empty() ? "" : " and model-form", fit_line(d.final_fit));
  for (std::size_t i = 0; i < d.se_model_form.size() && i < d.final_fit.names.size(); ++i)
    s += fmt::format("  {}: SE of ln p statistical {:.3f}, numerical {:.3f}, model-form {:.3f} (the "
                     "larger of the posture jackknife {:.3f} and the patch jackknife {:.3f}), total "
                     "{:.3f}\n",
                     d.final_fit.names[i], at(d.se_statistical, i), at(d.se_numerical, i),
                     d.se_model_form[i], at(d.se_posture_jackknife, i), at(d.se_patch_jackknife, i),
                     d.final_fit.uncertainty.se_log[i]);
  s += "\n" + d.verdict + "\n";
  s += fmt::format("({} posture solves, {:.1f} s)\n", d.posture_solves, d.seconds);
  return s;
}
} // namespace breastsim::diagnosis
