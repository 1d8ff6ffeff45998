// SPDX-License-Identifier: LGPL-3.0-or-later
#include "solved_held_out.hpp"
#include "linearised_refit.hpp"
#include "log.hpp"

namespace breastsim::diagnosis
{
namespace
{
/// Leaves every posture but `k` out of ev's solves while it lives; restores
/// the exclusions it found.
class OnlyPosture
{
public:
  OnlyPosture(PointEvaluator& ev, std::size_t k, std::size_t np) : ev_(ev), was_excluded_(np)
  {
    for (std::size_t p = 0; p < np; ++p)
    {
      was_excluded_[p] = ev.excluded(p);
      if (p != k)
        ev.exclude(p);
    }
  }
  ~OnlyPosture()
  {
    for (std::size_t p = 0; p < was_excluded_.size(); ++p)
      if (!was_excluded_[p])
        ev_.include(p);
  }
  OnlyPosture(const OnlyPosture&) = delete;
  OnlyPosture& operator=(const OnlyPosture&) = delete;

private:
  PointEvaluator& ev_;
  std::vector<bool> was_excluded_;
};

/// Posture k's chi2 of case `c`, solved alone; none when its solve fails.
std::optional<double> posture_chi2(PointEvaluator& ev, const Config& c, std::size_t k,
                                   std::size_t np, const std::vector<std::size_t>& rows)
{
  const OnlyPosture only(ev, k, np);
  const PointEvaluation e = ev.try_each(c);
  if (!e.solved[k])
    return std::nullopt;
  double chi2 = 0;
  for (std::size_t i : rows)
    chi2 += e.r[i] * e.r[i];
  return chi2;
}
} // namespace

SolvedChi2 solved_held_out_chi2(PointEvaluator& ev, const HeldOutModel& m, const Recording& rec)
{
  const auto rows = rows_by_posture(m.fit, rec);
  const auto y = log_values(m.fit);
  SolvedChi2 out(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
  {
    if (ev.excluded(k))
      continue;
    const auto yk = step_within_bounds(y, step_without(m.fit, mask_of(m.fit, rows[k])), m.frees);
    out[k] = posture_chi2(ev, config_at(m.base, m.frees, yk), k, rows.size(), rows[k]);
    if (out[k])
      log::info("posture '{}' held out: chi2 {:.1f} solved", rec.postures[k].name, *out[k]);
    else
      log::warn("posture '{}': its held-out prediction could not be solved", rec.postures[k].name);
  }
  return out;
}

void set_solved_gains(const SolvedChi2& without, const SolvedChi2& with, Evidence& e)
{
  e.held_out_gain_linearised = e.held_out_gain;
  for (std::size_t k = 0; k < e.held_out_gain.size() && k < without.size() && k < with.size(); ++k)
    if (without[k] && with[k])
      e.held_out_gain[k] = *without[k] - *with[k];
  e.held_out_solved = true;
}
} // namespace breastsim::diagnosis
