// SPDX-License-Identifier: LGPL-3.0-or-later
#include "evidence.hpp"
#include "candidates.hpp"
#include "linearised_refit.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

namespace breastsim::diagnosis
{
void effect_size(const FitState& without, const FitState& with, Evidence& e)
{
  double ss_all = 0;
  std::size_t n_all = 0;
  e.effect_rms_mm.clear();
  e.effect_max_mm.clear();
  for (std::size_t p = 0; p < with.distances.size() && p < without.distances.size(); ++p)
  {
    double ss = 0, mx = 0;
    const auto& a = without.distances[p];
    const auto& b = with.distances[p];
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
    {
      const double d = b[i] - a[i];
      ss += d * d;
      mx = std::max(mx, std::abs(d));
    }
    e.effect_rms_mm.push_back(1e3 * std::sqrt(ss / std::max<std::size_t>(a.size(), 1)));
    e.effect_max_mm.push_back(1e3 * mx);
    ss_all += ss;
    n_all += a.size();
  }
  e.effect_rms_mm_all = 1e3 * std::sqrt(ss_all / std::max<std::size_t>(n_all, 1));
  e.effect_rms_mm_largest = e.effect_rms_mm.empty()
                                ? 0.0
                                : *std::max_element(e.effect_rms_mm.begin(), e.effect_rms_mm.end());
}

double effect_at_interval_edge(const FitState& with, const std::string& parameter, double effect)
{
  const auto it = std::find(with.names.begin(), with.names.end(), parameter);
  const std::size_t i = it - with.names.begin();
  if (it == with.names.end() || i >= with.uncertainty.interval.size() || !(with.values[i] > 0))
    return 0.0;
  const double lo = with.uncertainty.interval[i][0];
  return std::isfinite(lo) ? effect * std::clamp(lo / with.values[i], 0.0, 1.0) : 0.0;
}

std::vector<double> held_out_chi2(const FitState& s, const Recording& rec)
{
  std::vector<double> out;
  for (const auto& rows : rows_by_posture(s, rec))
  {
    const auto held = mask_of(s, rows);
    out.push_back(predicted_chi2(s, held, step_without(s, held)));
  }
  return out;
}

double continuum_lr(double lr_h, double lr_fine, double ratio, double order)
{
  const double a = std::sqrt(std::max(lr_h, 0.0)), b = std::sqrt(std::max(lr_fine, 0.0));
  const double s0 = b + (b - a) / (std::pow(ratio, order) - 1.0);
  return s0 > 0 ? s0 * s0 : 0.0;
}

std::optional<std::string> held_out_refusal(const Evidence& e, const DiagnoseOptions& o)
{
  // The summed chi2 gain is positive, and so is the gain of more than half
  // of the postures (one posture cannot carry a stand-in).
  const double gain = std::accumulate(e.held_out_gain.begin(), e.held_out_gain.end(), 0.0);
  const auto improved = std::count_if(e.held_out_gain.begin(), e.held_out_gain.end(),
                                      [](double g) { return g > 0; });
  const auto postures = static_cast<long>(e.held_out_gain.size());
  const char* how = e.held_out_solved ? "solved" : "linearised";
  if (!o.held_out_check || postures == 0)
    return std::nullopt;
  if (!(gain > 0))
    return fmt::format("it does not improve the prediction of held-out postures "
                       "(chi2 gain {:.1f}, {})", gain, how);
  if (2 * improved <= postures)
    return fmt::format("it improves the prediction of only {} of {} held-out postures "
                       "(a term must improve more than half of them; {})", improved, postures, how);
  return std::nullopt;
}

double refinement_critical(double statistical, double allowance) { return statistical + allowance; }

bool survives_refinement(const Evidence& e)
{
  return e.lr_fine > e.critical_fine && e.lr_continuum > e.critical_continuum;
}

void judge(Evidence& e, const DiagnoseOptions& o, double noise_sigma)
{
  e.failed.clear();
  if (!(e.lr > e.critical))
    e.failed.push_back(fmt::format("its LR {:.1f} is below the critical value {:.1f}", e.lr, e.critical));
  const double min_mm = 1e3 * o.min_effect * noise_sigma;
  const double effect = e.effect_rms_mm_all;
  if (o.min_effect > 0 && effect < min_mm)
    e.failed.push_back(fmt::format("its effect, RMS {:.3f} mm, is below {:g} x the noise ({:.3f} mm)",
                                   effect, o.min_effect, min_mm));
  else if (o.min_effect > 0 && e.effect_at_null_edge_mm < min_mm)
    e.failed.push_back(fmt::format("its 95 % interval reaches the null: at the interval's end the "
                                   "effect is {:.3f} mm, below {:.3f} mm",
                                   e.effect_at_null_edge_mm, min_mm));
  if (auto why = held_out_refusal(e, o))
    e.failed.push_back(*why);
  // Model-form share: LR >= share (chi2 - dof) of the model before the term
  // (a stricter share after a term was found: its shape error is in that misfit).
  const double misfit_share = e.misfit_before > 0 ? e.lr / e.misfit_before : 1.0;
  const double min_share = e.terms_before > 0 ? o.min_misfit_share_later : o.min_misfit_share;
  if (min_share > 0 && misfit_share < min_share)
    e.failed.push_back(fmt::format("it explains {:.0f} % of the misfit it is tested against (LR {:.1f} of "
                                   "chi2 - dof = {:.1f}), less than {:g} %{}: the rest has a shape no "
                                   "candidate has, and the term would stand in for it",
                                   100 * misfit_share, e.lr, e.misfit_before, 100 * min_share,
                                   e.terms_before > 0 ? " (after a found term)" : ""));
  if (e.refinement_checked && !survives_refinement(e))
    e.failed.push_back(fmt::format("its LR does not survive refinement: {:.1f} on the finer mesh "
                                   "against {:.1f}, {:.1f} extrapolated to the continuum against {:.1f}",
                                   e.lr_fine, e.critical_fine, e.lr_continuum, e.critical_continuum));
}

std::string evidence_text(const Evidence& e)
{
  std::string t = fmt::format("  {}: LR {:.1f} (critical {:.1f}); effect RMS {:.3f} mm over all points, "
                              "{:.3f} mm in the posture it changes most (per posture",
                              e.candidate, e.lr, e.critical, e.effect_rms_mm_all, e.effect_rms_mm_largest);
  for (std::size_t p = 0; p < e.effect_rms_mm.size(); ++p)
    t += fmt::format("{} {:.3f}/max {:.3f}", p ? "," : "", e.effect_rms_mm[p], e.effect_max_mm[p]);
  t += fmt::format("), {:.3f} mm at the interval's end nearest the null", e.effect_at_null_edge_mm);
  t += fmt::format("; held-out chi2 gain per posture ({})", e.held_out_solved ? "solved" : "linearised");
  for (std::size_t p = 0; p < e.held_out_gain.size(); ++p)
    t += fmt::format("{} {:.1f}", p ? "," : "", e.held_out_gain[p]);
  if (e.misfit_before > 0)
    t += fmt::format("; {:.0f} % of the misfit before it (chi2 - dof = {:.1f})", 100 * e.lr / e.misfit_before,
                     e.misfit_before);
  if (e.refinement_checked)
    t += fmt::format("; LR on the finer mesh {:.1f} (critical {:.1f}), in the continuum {:.1f} (critical {:.1f})",
                     e.lr_fine, e.critical_fine, e.lr_continuum, e.critical_continuum);
  if (e.failed.empty())
    t += e.accepted ? ".\n    -> accepted: every rule holds.\n"
                    : ".\n    -> not added: another candidate with a larger margin was accepted first.\n";
  else
    t += ".\n    -> rejected:";
  for (std::size_t k = 0; k < e.failed.size(); ++k)
    t += fmt::format("{} {}{}", k ? ";" : "", e.failed[k], k + 1 == e.failed.size() ? ".\n" : "");
  return t;
}

nlohmann::json to_json(const Evidence& e)
{
  nlohmann::json j = {{"candidate", e.candidate},
                      {"physics", candidate(e.candidate).family},
                      {"likelihood_ratio", e.lr},
                      {"critical_value", e.critical},
                      {"effect_rms_mm", e.effect_rms_mm},
                      {"effect_max_mm", e.effect_max_mm},
                      {"effect_rms_mm_all", e.effect_rms_mm_all},
                      {"effect_rms_mm_largest_posture", e.effect_rms_mm_largest},
                      {"effect_at_null_edge_mm", e.effect_at_null_edge_mm},
                      {"held_out_chi2_gain", e.held_out_gain},
                      {"misfit_before", e.misfit_before},
                      {"accepted", e.accepted},
                      {"rejected_because", e.failed}};
  if (e.held_out_solved)
    j["held_out_chi2_gain_linearised"] = e.held_out_gain_linearised;
  j["held_out_solved"] = e.held_out_solved;
  if (e.refinement_checked)
  {
    j["likelihood_ratio_fine"] = e.lr_fine;
    j["likelihood_ratio_continuum"] = e.lr_continuum;
    j["critical_value_fine"] = e.critical_fine;
    j["critical_value_continuum"] = e.critical_continuum;
    j["refinement_passed"] = survives_refinement(e);
  }
  return j;
}
} // namespace breastsim::diagnosis
