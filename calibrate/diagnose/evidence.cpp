#include "evidence.hpp"
#include "least_squares.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

namespace breastsim::calibration
{
namespace
{
/// The residual rows of each posture: its points, then its landmark rows.
std::vector<std::vector<std::size_t>> rows_by_posture(const FitState& s, const Recording& rec)
{
  std::vector<std::vector<std::size_t>> rows(s.distances.size());
  std::size_t j = 0;
  for (std::size_t p = 0; p < s.distances.size(); ++p)
    for (std::size_t i = 0; i < s.distances[p].size(); ++i)
      rows[p].push_back(j++);
  for (std::size_t p = 0; p < rec.postures.size() && p < rows.size(); ++p)
    if (rec.postures[p].nipple)
      for (int k = 0; k < 3; ++k)
        rows[p].push_back(j++);
  return rows;
}

/// The Gauss-Newton step in ln p fitted on the rows not in `held`:
/// delta = -(J_-k^T J_-k)^-1 J_-k^T r_-k (zero if singular).
std::vector<double> step_without(const FitState& s, const std::vector<char>& held)
{
  const std::size_t n = s.J.empty() ? 0 : s.J[0].size();
  Matrix A(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0), delta(n, 0.0);
  for (std::size_t i = 0; i < s.r.size(); ++i)
    if (!held[i])
      for (std::size_t p = 0; p < n; ++p)
      {
        b[p] -= s.J[i][p] * s.r[i];
        for (std::size_t q = 0; q < n; ++q)
          A[p][q] += s.J[i][p] * s.J[i][q];
      }
  if (n > 0 && !solve_dense(A, b, delta))
    delta.assign(n, 0.0);
  return delta;
}

/// |r_k + J_k delta|^2 over the rows marked in `held`.
double predicted_chi2(const FitState& s, const std::vector<char>& held, const std::vector<double>& delta)
{
  const std::size_t n = delta.size();
  double chi2 = 0;
  for (std::size_t i = 0; i < s.r.size(); ++i)
    if (held[i])
    {
      double ri = s.r[i];
      for (std::size_t p = 0; p < n; ++p)
        ri += s.J[i][p] * delta[p];
      chi2 += ri * ri;
    }
  return chi2;
}
} // namespace

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

namespace
{
/// Rows of posture k marked, for each posture.
std::vector<std::vector<char>> held_masks(const FitState& s, const Recording& rec)
{
  std::vector<std::vector<char>> masks;
  for (const auto& rows : rows_by_posture(s, rec))
  {
    masks.emplace_back(s.r.size(), 0);
    for (std::size_t i : rows)
      if (i < s.r.size())
        masks.back()[i] = 1;
  }
  return masks;
}
} // namespace

std::vector<double> held_out_chi2(const FitState& s, const Recording& rec)
{
  std::vector<double> out;
  for (const auto& held : held_masks(s, rec))
    out.push_back(predicted_chi2(s, held, step_without(s, held)));
  return out;
}

std::vector<double> posture_jackknife_se(const FitState& s, const Recording& rec)
{
  const auto masks = held_masks(s, rec);
  const std::size_t n = s.values.size(), k = masks.size();
  std::vector<std::vector<double>> steps;
  for (const auto& held : masks)
    steps.push_back(step_without(s, held));
  std::vector<double> se(n, 0.0);
  for (std::size_t p = 0; p < n && k > 1; ++p)
  {
    double mean = 0, ss = 0;
    for (const auto& d : steps)
      mean += d[p] / static_cast<double>(k);
    for (const auto& d : steps)
      ss += (d[p] - mean) * (d[p] - mean);
    se[p] = std::sqrt(ss * static_cast<double>(k - 1) / static_cast<double>(k));
  }
  return se;
}

void widen_by_model_form(FitState& s, const std::vector<double>& se_model_form)
{
  auto& u = s.uncertainty;
  for (std::size_t i = 0; i < s.values.size() && i < u.se_log.size() && i < se_model_form.size(); ++i)
  {
    widen_interval(u, i, s.values[i], se_model_form[i]);
  }
}

double continuum_lr(double lr_h, double lr_fine, double ratio, double order)
{
  const double a = std::sqrt(std::max(lr_h, 0.0)), b = std::sqrt(std::max(lr_fine, 0.0));
  const double s0 = b + (b - a) / (std::pow(ratio, order) - 1.0);
  return s0 > 0 ? s0 * s0 : 0.0;
}

void judge(Evidence& e, const DiagnoseOptions& o, double noise_sigma)
{
  e.failed.clear();
  if (!(e.lr > e.critical))
    e.failed.push_back(fmt::format("its LR {:.1f} is below the critical value {:.1f}", e.lr, e.critical));
  const double min_mm = 1e3 * o.min_effect * noise_sigma;
  if (o.min_effect > 0 && e.effect_rms_mm_all < min_mm)
    e.failed.push_back(fmt::format("its effect, RMS {:.3f} mm, is below {:g} x the noise ({:.3f} mm)",
                                   e.effect_rms_mm_all, o.min_effect, min_mm));
  else if (o.min_effect > 0 && e.effect_at_null_edge_mm < min_mm)
    e.failed.push_back(fmt::format("its 95 % interval reaches the null: at the interval's end the "
                                   "effect is {:.3f} mm, below {:.3f} mm",
                                   e.effect_at_null_edge_mm, min_mm));
  const double gain = std::accumulate(e.held_out_gain.begin(), e.held_out_gain.end(), 0.0);
  if (o.held_out_check && !e.held_out_gain.empty() && !(gain > 0))
    e.failed.push_back(fmt::format("it does not improve the prediction of held-out postures "
                                   "(chi2 gain {:.1f})", gain));
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
  if (e.refinement_checked && !(e.lr_fine > e.critical && e.lr_continuum > e.critical))
    e.failed.push_back(fmt::format("its LR does not survive refinement: {:.1f} on the finer mesh, "
                                   "{:.1f} extrapolated to the continuum, against {:.1f}",
                                   e.lr_fine, e.lr_continuum, e.critical));
}

std::string evidence_text(const Evidence& e)
{
  std::string t = fmt::format("  {}: LR {:.1f} (critical {:.1f}); effect RMS {:.3f} mm (per posture",
                              e.candidate, e.lr, e.critical, e.effect_rms_mm_all);
  for (std::size_t p = 0; p < e.effect_rms_mm.size(); ++p)
    t += fmt::format("{} {:.3f}/max {:.3f}", p ? "," : "", e.effect_rms_mm[p], e.effect_max_mm[p]);
  t += fmt::format("), {:.3f} mm at the interval's end nearest the null", e.effect_at_null_edge_mm);
  t += "; held-out chi2 gain per posture";
  for (std::size_t p = 0; p < e.held_out_gain.size(); ++p)
    t += fmt::format("{} {:.1f}", p ? "," : "", e.held_out_gain[p]);
  if (e.misfit_before > 0)
    t += fmt::format("; {:.0f} % of the misfit before it (chi2 - dof = {:.1f})", 100 * e.lr / e.misfit_before,
                     e.misfit_before);
  if (e.refinement_checked)
    t += fmt::format("; LR on the finer mesh {:.1f}, in the continuum {:.1f}", e.lr_fine, e.lr_continuum);
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
                      {"likelihood_ratio", e.lr},
                      {"critical_value", e.critical},
                      {"effect_rms_mm", e.effect_rms_mm},
                      {"effect_max_mm", e.effect_max_mm},
                      {"effect_rms_mm_all", e.effect_rms_mm_all},
                      {"effect_at_null_edge_mm", e.effect_at_null_edge_mm},
                      {"held_out_chi2_gain", e.held_out_gain},
                      {"misfit_before", e.misfit_before},
                      {"accepted", e.accepted},
                      {"rejected_because", e.failed}};
  if (e.refinement_checked)
  {
    j["likelihood_ratio_fine"] = e.lr_fine;
    j["likelihood_ratio_continuum"] = e.lr_continuum;
  }
  return j;
}
} // namespace breastsim::calibration
