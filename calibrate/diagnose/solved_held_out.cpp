#include "solved_held_out.hpp"
#include "evidence.hpp"
#include "linearised_refit.hpp"
#include "log.hpp"
#include <algorithm>
#include <cmath>
#include <optional>

namespace breastsim::calibration
{
namespace
{
/// Posture k's chi2 of case `c`, solved with every other of the `np`
/// postures left out; none when its solve fails.
std::optional<double> posture_chi2(PointEvaluator& ev, const Config& c, std::size_t k,
                                   std::size_t np, const std::vector<std::size_t>& rows)
{
  std::vector<bool> was_excluded(np);
  for (std::size_t p = 0; p < np; ++p)
  {
    was_excluded[p] = ev.excluded(p);
    if (p != k)
      ev.exclude(p);
  }
  const PointEvaluation e = ev.try_each(c);
  for (std::size_t p = 0; p < np; ++p)
    if (!was_excluded[p])
      ev.include(p);
  if (!e.solved[k])
    return std::nullopt;
  double chi2 = 0;
  for (std::size_t i : rows)
    chi2 += e.r[i] * e.r[i];
  return chi2;
}
} // namespace

std::vector<double> solved_held_out_chi2(PointEvaluator& ev, const Config& base,
                                         const std::vector<Free>& frees, const FitState& s,
                                         const Recording& rec, const std::vector<double>& linearised)
{
  const auto rows = rows_by_posture(s, rec);
  const auto y = log_values(s);
  std::vector<double> out;
  for (std::size_t k = 0; k < rows.size() && k < linearised.size(); ++k)
  {
    if (ev.excluded(k))
    {
      out.push_back(linearised[k]);
      continue;
    }
    const auto delta = step_without(s, mask_of(s, rows[k]));
    auto yk = y;
    for (std::size_t p = 0; p < yk.size() && p < delta.size() && p < frees.size(); ++p)
      yk[p] = std::clamp(yk[p] + delta[p], std::log(frees[p].lo), std::log(frees[p].hi));
    const auto chi2 = posture_chi2(ev, config_at(base, frees, yk), k, rows.size(), rows[k]);
    if (!chi2)
      log::warn("posture '{}': its held-out prediction could not be solved; the linearised one is kept",
                rec.postures[k].name);
    out.push_back(chi2.value_or(linearised[k]));
    log::info("posture '{}' held out: chi2 {:.1f} solved, {:.1f} linearised", rec.postures[k].name,
              out.back(), linearised[k]);
  }
  return out;
}

void solve_held_out_gains(PointEvaluator& ev, const HeldOutModel& without, const HeldOutModel& with,
                          const Recording& rec, Evidence& e)
{
  const auto a = solved_held_out_chi2(ev, without.base, without.frees, without.fit, rec,
                                      held_out_chi2(without.fit, rec));
  const auto b = solved_held_out_chi2(ev, with.base, with.frees, with.fit, rec, held_out_chi2(with.fit, rec));
  e.held_out_gain_linearised = e.held_out_gain;
  e.held_out_gain.clear();
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
    e.held_out_gain.push_back(a[k] - b[k]);
  e.held_out_solved = true;
}
} // namespace breastsim::calibration
