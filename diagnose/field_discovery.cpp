// SPDX-License-Identifier: LGPL-3.0-or-later
#include "field_discovery.hpp"
#include "candidate_scores.hpp"
#include "errors.hpp"
#include "evidence.hpp"
#include "geometry_options.hpp"
#include "linearised_refit.hpp"
#include "log.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

namespace breastsim::diagnosis
{
namespace
{
constexpr double max_amplitude = 4.0; ///< |a_k| <= 4: a basis function's peak exp(+-4)

/// a_k as a free parameter p = exp(y) with y = a_k (fit_state.hpp works in ln p).
Free amplitude(std::size_t k)
{
  return {fmt::format("field.a{}", k + 1), "1", std::exp(-max_amplitude), std::exp(max_amplitude),
          [k](Config& c, double v)
          {
            auto a = c.numbers("tissue_field.amplitudes");
            a[k] = std::log(v);
            c.set("tissue_field.amplitudes", a);
          },
          1.0};
}

/// The columns [first, first + n) of J.
Matrix columns(const Matrix& J, std::size_t first, std::size_t n)
{
  Matrix out(J.size(), std::vector<double>(n));
  for (std::size_t i = 0; i < J.size(); ++i)
    for (std::size_t j = 0; j < n; ++j)
      out[i][j] = J[i][first + j];
  return out;
}

/// Covariance of the parameters [first, ...) of a fit: corr_jk SE_j SE_k.
Matrix covariance_from(const Uncertainty& u, std::size_t first)
{
  const std::size_t n = u.se_log.size() > first ? u.se_log.size() - first : 0;
  Matrix C(n, std::vector<double>(n, 0.0));
  if (u.correlation.size() != u.se_log.size())
    return {};
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k)
      C[j][k] = u.correlation[first + j][first + k] * u.se_log[first + j] * u.se_log[first + k];
  return C;
}

/// Steps 3-4: the penalised fit from the linearised one, and its rules.
void fit_and_judge(FieldDiscovery& f, PointEvaluator& ev, const Recording& rec,
                   const std::vector<Free>& all, std::size_t m, const std::vector<double>& means,
                   const FitState& state, const DiagnoseOptions& o)
{
  std::vector<double> y = log_values(state);
  y = step_within_bounds(y, f.ridge.d, std::vector<Free>(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(m)));
  for (double a : f.ridge.a)
    y.push_back(std::clamp(a, -max_amplitude, max_amplitude));
  const Config base = with_field(state.config, f.basis, {});
  f.after = fit(ev, base, all, y, o.lsq, "field fit",
                Ridge{m, f.ridge.lambda, means, zero_mean_weight * f.ridge.scale});
  for (std::size_t k = m; k < f.after.values.size(); ++k)
    f.amplitudes.push_back(std::log(f.after.values[k]));
  f.amplitude_cov = covariance_from(f.after.uncertainty, m);
  f.lr = state.chi2 - f.after.chi2;
  f.critical = chi2_critical(std::max(f.ridge.dof, 1.0), o.alpha);
  Evidence e;
  effect_size(state, f.after, e);
  f.effect_rms_mm = e.effect_rms_mm_all;
  if (!(f.lr > f.critical))
    f.failed.push_back(fmt::format("LR {:.1f} below the critical {:.1f} (chi2 of {:.1f} effective "
                                   "parameters at {:g})", f.lr, f.critical, f.ridge.dof, o.alpha));
  const auto losing = std::count_if(f.ridge.held_out_gain.begin(), f.ridge.held_out_gain.end(),
                                    [](double g) { return g <= 0; });
  if (!(f.ridge.total_gain > 0) || losing > 1)
    f.failed.push_back(fmt::format("the held-out postures gain {:.1f} in all, {} of {} none",
                                   f.ridge.total_gain, losing, f.ridge.held_out_gain.size()));
  const double min_mm = 1e3 * o.min_effect * rec.noise_sigma;
  if (f.effect_rms_mm < min_mm)
    f.failed.push_back(fmt::format("it changes the surface by {:.3f} mm RMS, below {:.3f} mm",
                                   f.effect_rms_mm, min_mm));
  f.accepted = f.failed.empty();
}
} // namespace

FieldDiscovery discover_field(PointEvaluator& ev, const Recording& rec,
                              const std::vector<Free>& frees, const FitState& state,
                              const DiagnoseOptions& o)
{
  FieldDiscovery f;
  if (!(state.gof_p < o.alpha))
  {
    f.skipped = fmt::format("the model fits to the noise (p = {:.2g})", state.gof_p);
    return f;
  }
  if (rec.postures.size() < 2)
  {
    f.skipped = "choosing the field's smoothness needs a held-out posture (two postures or more)";
    return f;
  }
  f.tried = true;
  const HalfCapSpec cap = HalfCapSpec::from(state.config);
  f.basis = lattice_basis(cap.R, cap.H);
  const std::size_t m = frees.size(), K = f.basis.centres.size();
  std::vector<Free> all = frees;
  for (std::size_t k = 0; k < K; ++k)
    all.push_back(amplitude(k));
  std::vector<double> y = log_values(state);
  y.resize(m + K, 0.0);
  try
  {
    int evaluations = 0; // step 1: the exact columns at a = 0
    const Matrix J = fit_jacobian(ev, with_field(state.config, f.basis, {}), all, y, state.r,
                                  o.lsq.fd_step, evaluations);
    const auto means = basis_means(f.basis, cap.R, cap.H);
    f.ridge = choose_ridge(columns(J, m, K), columns(J, 0, m), state.r, rows_by_posture(state, rec), means);
    log::info("field: ridge lambda {:.3g} chosen on held-out postures (gain {:.1f}, {:.1f} effective "
              "parameters)", f.ridge.lambda, f.ridge.total_gain, f.ridge.dof);
    fit_and_judge(f, ev, rec, all, m, means, state, o);
  }
  catch (const SolveError& err)
  {
    f.failed.push_back(fmt::format("its fit failed ({})", err.what()));
    return f;
  }
  f.summary = summarise_field(f.basis, f.amplitudes, f.amplitude_cov, cap.R, cap.H);
  log::info("field: LR {:.1f} against {:.1f}: {}; {}", f.lr, f.critical,
            f.accepted ? "accepted" : "rejected", f.summary.words);
  return f;
}

std::string field_verdict(const FieldDiscovery& f, const FitState& before)
{
  if (!f.tried)
    return "";
  if (!f.accepted)
    return fmt::format(" A smooth stiffness field does not model the rest either: {}.",
                       fmt::join(f.failed, "; "));
  return fmt::format(" The rest is modelled as a stiffness field: {}; chi2/dof {:.3f} -> {:.3f} "
                     "(found_stiffness.py, case.field.toml).",
                     f.summary.words, before.chi2 / std::max(before.dof, 1),
                     f.after.chi2 / std::max(f.after.dof, 1));
}

std::string field_text(const FieldDiscovery& f, const Recording& rec)
{
  if (!f.tried)
    return f.skipped.empty() ? "" : fmt::format("\nFIELD: not tried: {}\n", f.skipped);
  std::string s = fmt::format("\nFIELD: the rest modelled as a smooth stiffness field exp(s(X)) x tissue "
                              "({} Gaussian basis functions of width {:.1f} mm)\n",
                              f.basis.centres.size(), 1e3 * f.basis.width);
  if (f.after.names.empty())
    return s + fmt::format("  not modelled: {}\n", fmt::join(f.failed, "; "));
  std::string gains;
  for (std::size_t p = 0; p < f.ridge.held_out_gain.size() && p < rec.postures.size(); ++p)
    gains += fmt::format("{}{} {:+.1f}", p ? ", " : "", rec.postures[p].name, f.ridge.held_out_gain[p]);
  s += fmt::format("  smoothness chosen on held-out postures: lambda {:.3g}, {:.1f} effective "
                   "parameters; held-out chi2 gains {}\n",
                   f.ridge.lambda, f.ridge.dof, gains);
  s += fmt::format("  chi2 {:.1f} -> {:.1f}: LR {:.1f} against the critical {:.1f}; surface change "
                   "{:.3f} mm RMS; chi2/dof now {:.3f}\n",
                   f.after.chi2 + f.lr, f.after.chi2, f.lr, f.critical, f.effect_rms_mm,
                   f.after.chi2 / std::max(f.after.dof, 1));
  s += fmt::format("  {}: {}\n", f.accepted ? "modelled" : "not modelled",
                   f.accepted ? f.summary.words : fmt::format("{}", fmt::join(f.failed, "; ")));
  if (f.accepted)
    s += "  written as a UFL term: found_stiffness.py (forms/: the file plus one line in "
         "forms/registry.py); the model with it: case.field.toml\n";
  return s;
}

nlohmann::json to_json(const FieldDiscovery& f)
{
  nlohmann::json j;
  j["tried"] = f.tried;
  j["accepted"] = f.accepted;
  j["family"] = "tissue_field"; // the physics it names (forms/tissue_field.py)
  j["skipped"] = f.skipped;
  j["failed"] = f.failed;
  if (!f.tried)
    return j;
  std::vector<std::array<double, 3>> centres;
  for (const auto& c : f.basis.centres)
    centres.push_back({c[0], c[1], c[2]});
  j["basis"] = {{"centres_m", centres}, {"width_m", f.basis.width}};
  j["amplitudes"] = f.amplitudes;
  j["ridge"] = {{"lambda", f.ridge.lambda}, {"effective_parameters", f.ridge.dof},
                {"held_out_gain", f.ridge.held_out_gain}, {"held_out_gain_total", f.ridge.total_gain},
                {"path", f.ridge.path}};
  j["likelihood_ratio"] = f.lr;
  j["critical_value"] = f.critical;
  j["effect_rms_mm"] = f.effect_rms_mm;
  j["chi2_after"] = f.after.chi2;
  j["dof_after"] = f.after.dof;
  const auto& S = f.summary;
  j["summary"] = {{"bulk_factor", S.bulk_factor}, {"peak_m", S.peak}, {"factor", S.factor}, {"factor_interval", {S.factor_lo, S.factor_hi}},
                  {"centroid_m", S.centroid}, {"extent_mm", S.extent_mm},
                  {"volume_share", S.volume_share}, {"where", S.where}, {"resembles", S.resembles},
                  {"words", S.words}};
  return j;
}
} // namespace breastsim::diagnosis
