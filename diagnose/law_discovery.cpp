// SPDX-License-Identifier: LGPL-3.0-or-later
#include "law_discovery.hpp"
#include "candidate_scores.hpp"
#include "errors.hpp"
#include "evidence.hpp"
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
constexpr const char* key = "tissue_law.coefficients";

/// b_k as a free parameter p = exp(y) of the fit, within [1e-5, 1e3] x mu.
Free coefficient(std::size_t k, double mu)
{
  return {fmt::format("law.b{}", k + 1), "Pa", 1e-5 * mu, 1e3 * mu,
          [k](Config& c, double v)
          {
            auto b = c.numbers(key);
            b[k] = v;
            c.set(key, b);
          },
          1e-2 * mu};
}

/// `c` with the law's term on and coefficients b.
Config with_law(Config c, const std::vector<double>& b)
{
  c.set("terms.tissue_law", true);
  c.set(key, b);
  return c;
}

/// dr/db_k at b = 0 (whitened, per Pa) of every feature: central residual
/// differences of step 1e-3 mu (exact: the energy is linear in b).
Matrix feature_columns(PointEvaluator& ev, const Config& c, double mu)
{
  const std::size_t K = law_feature_names().size();
  std::vector<ForwardModel::CaseDifference> directions;
  for (std::size_t k = 0; k < K; ++k)
  {
    std::vector<double> plus(K, 0.0), minus(K, 0.0);
    plus[k] = 1e-3 * mu;
    minus[k] = -1e-3 * mu;
    directions.push_back({with_law(c, plus), with_law(c, minus), 2e-3 * mu});
  }
  return ev.jacobian(c, directions);
}

/// Steps 3-4: the fit of the chosen features and the rules.
void fit_and_judge(LawDiscovery& l, PointEvaluator& ev, const Recording& rec,
                   const std::vector<Free>& frees, const FitState& state, const DiagnoseOptions& o)
{
  std::vector<Free> all = frees;
  std::vector<double> y = step_within_bounds(log_values(state), l.choice.d, frees);
  for (std::size_t j = 0; j < l.choice.features.size(); ++j)
  {
    all.push_back(coefficient(l.choice.features[j], l.mu));
    y.push_back(std::log(std::clamp(l.choice.b[j] * l.mu, all.back().lo * 10, all.back().hi)));
  }
  const Config base = with_law(state.config, std::vector<double>(law_feature_names().size(), 0.0));
  l.after = fit(ev, base, all, y, o.lsq, "law fit");
  l.coefficients = l.after.config.numbers(key);
  l.mu = l.after.config.number("tissue.mu");
  l.lr = state.chi2 - l.after.chi2;
  l.critical = chi2_critical(static_cast<double>(l.choice.features.size()), o.alpha);
  Evidence e;
  effect_size(state, l.after, e);
  l.effect_rms_mm = e.effect_rms_mm_all;
  if (!(l.lr > l.critical))
    l.failed.push_back(fmt::format("LR {:.1f} below the critical {:.1f}", l.lr, l.critical));
  const auto losing = std::count_if(l.choice.held_out_gain.begin(), l.choice.held_out_gain.end(),
                                    [](double g) { return g <= 0; });
  if (losing > 1)
    l.failed.push_back(fmt::format("{} of {} held-out postures gain nothing", losing,
                                   l.choice.held_out_gain.size()));
  const double min_mm = 1e3 * o.min_effect * rec.noise_sigma;
  if (l.effect_rms_mm < min_mm)
    l.failed.push_back(fmt::format("it changes the surface by {:.3f} mm RMS, below {:.3f} mm",
                                   l.effect_rms_mm, min_mm));
  l.accepted = l.failed.empty();
}
} // namespace

const std::vector<std::string>& law_feature_names()
{
  static const std::vector<std::string> names = {"(I1b - 3)^2", "(I1b - 3)^3", "I2b - 3"};
  return names;
}

double law_energy_ratio(const std::vector<double>& b, double mu, double stretch)
{
  const double l = stretch, i1 = l * l + 2 / l - 3, i2 = 2 * l + 1 / (l * l) - 3;
  const double f[3] = {i1 * i1, i1 * i1 * i1, i2};
  double w = 0;
  for (std::size_t k = 0; k < 3 && k < b.size(); ++k)
    w += b[k] * f[k];
  return 1 + w / (mu / 2 * i1); // W_nh = mu/2 (I1b - 3) at J = 1
}

std::string law_words(const std::vector<double>& b, double mu)
{
  std::vector<std::string> parts;
  if (b.size() >= 2 && (b[0] > 0 || b[1] > 0))
    parts.push_back(fmt::format("the tissue stiffens with strain (Yeoh-like): in uniaxial stretch its "
                                "energy is {:.2f} x that of eq. (5) at 10 %, {:.2f} x at 20 %, {:.2f} x "
                                "at 30 %",
                                law_energy_ratio({b[0], b[1], 0.0}, mu, 1.1),
                                law_energy_ratio({b[0], b[1], 0.0}, mu, 1.2),
                                law_energy_ratio({b[0], b[1], 0.0}, mu, 1.3)));
  if (b.size() >= 3 && b[2] > 0)
    parts.push_back(fmt::format("a second-invariant (Mooney-Rivlin) part carries {:.0f} % of the "
                                "small-strain shear modulus (mu + 2 b_3 = {:.0f} Pa)",
                                100 * 2 * b[2] / (mu + 2 * b[2]), mu + 2 * b[2]));
  std::string s;
  for (std::size_t i = 0; i < parts.size(); ++i)
    s += (i ? "; " : "") + parts[i];
  return s.empty() ? "no feature beyond eq. (5)" : s;
}

LawDiscovery discover_law(PointEvaluator& ev, const Recording& rec, const std::vector<Free>& frees,
                          const FitState& state, const DiagnoseOptions& o)
{
  LawDiscovery l;
  if (!(state.gof_p < o.alpha))
  {
    l.skipped = fmt::format("the model fits to the noise (p = {:.2g})", state.gof_p);
    return l;
  }
  if (rec.postures.size() < 2)
  {
    l.skipped = "choosing the law's features needs a held-out posture (two postures or more)";
    return l;
  }
  l.tried = true;
  l.mu = state.config.number("tissue.mu");
  try
  {
    const std::size_t K = law_feature_names().size();
    Matrix A = feature_columns(ev, with_law(state.config, std::vector<double>(K, 0.0)), l.mu);
    for (auto& row : A) // per unit b / mu
      for (double& x : row)
        x *= l.mu;
    l.choice = choose_features(A, state.J, state.r, rows_by_posture(state, rec));
    if (l.choice.features.empty())
    {
      l.failed.push_back("no subset of the features gains on the held-out postures");
      return l;
    }
    fit_and_judge(l, ev, rec, frees, state, o);
  }
  catch (const SolveError& err)
  {
    l.failed.push_back(fmt::format("its fit failed ({})", err.what()));
    return l;
  }
  for (double s : {1.1, 1.2, 1.3})
    l.stiffening.emplace_back(s, law_energy_ratio(l.coefficients, l.mu, s));
  l.words = law_words(l.coefficients, l.mu);
  log::info("law: LR {:.1f} against {:.1f}: {}; {}", l.lr, l.critical,
            l.accepted ? "accepted" : "rejected", l.words);
  return l;
}

namespace
{
std::string chosen_names(const LawDiscovery& l)
{
  std::vector<std::string> n;
  for (std::size_t k : l.choice.features)
    n.push_back(law_feature_names()[k]);
  return fmt::format("{}", fmt::join(n, ", "));
}
} // namespace

std::string law_verdict(const LawDiscovery& l, const FitState& before)
{
  if (!l.tried)
    return "";
  if (!l.accepted)
    return fmt::format(" A tissue law beyond eq. (5) does not model the rest: {}.", fmt::join(l.failed, "; "));
  return fmt::format(" The rest is modelled by the tissue's law: {}; chi2/dof {:.3f} -> {:.3f} "
                     "(found_law.py, case.law.toml).",
                     l.words, before.chi2 / std::max(before.dof, 1), l.after.chi2 / std::max(l.after.dof, 1));
}

std::string law_text(const LawDiscovery& l, const Recording& rec)
{
  if (!l.tried)
    return l.skipped.empty() ? "" : fmt::format("\nLAW: not tried: {}\n", l.skipped);
  std::string s = "\nLAW: invariant features of the tissue's energy beyond eq. (5): "
                  + fmt::format("{}\n", fmt::join(law_feature_names(), ", "));
  if (l.choice.features.empty() || l.after.names.empty())
    return s + fmt::format("  not modelled: {}\n", fmt::join(l.failed, "; "));
  std::string gains;
  for (std::size_t p = 0; p < l.choice.held_out_gain.size() && p < rec.postures.size(); ++p)
    gains += fmt::format("{}{} {:+.1f}", p ? ", " : "", rec.postures[p].name, l.choice.held_out_gain[p]);
  s += fmt::format("  chosen on held-out postures: {}; held-out chi2 gains {}\n", chosen_names(l), gains);
  s += fmt::format("  chi2 {:.1f} -> {:.1f}: LR {:.1f} against the critical {:.1f}; surface change {:.3f} "
                   "mm RMS; b = [{}] Pa\n",
                   l.after.chi2 + l.lr, l.after.chi2, l.lr, l.critical, l.effect_rms_mm,
                   fmt::join(l.coefficients, ", "));
  s += fmt::format("  {}: {}\n", l.accepted ? "modelled" : "not modelled",
                   l.accepted ? l.words : fmt::format("{}", fmt::join(l.failed, "; ")));
  if (l.accepted)
    s += "  written as a UFL term: found_law.py (forms/: the file plus one line in forms/registry.py); "
         "the model with it: case.law.toml\n";
  return s;
}

nlohmann::json to_json(const LawDiscovery& l)
{
  nlohmann::json j;
  j["tried"] = l.tried;
  j["accepted"] = l.accepted;
  j["family"] = "tissue_law"; // the physics it names (forms/tissue_law.py)
  j["skipped"] = l.skipped;
  j["failed"] = l.failed;
  if (!l.tried)
    return j;
  j["features"] = law_feature_names();
  j["chosen"] = l.choice.features;
  j["held_out_gain"] = l.choice.held_out_gain;
  nlohmann::json tried = nlohmann::json::array();
  for (const auto& [S, g] : l.choice.tried)
    tried.push_back({{"features", S}, {"held_out_gain", std::isfinite(g) ? nlohmann::json(g) : nlohmann::json()}});
  j["subsets"] = tried;
  j["coefficients_pa"] = l.coefficients;
  j["mu_pa"] = l.mu;
  j["likelihood_ratio"] = l.lr;
  j["critical_value"] = l.critical;
  j["effect_rms_mm"] = l.effect_rms_mm;
  j["chi2_after"] = l.after.chi2;
  j["dof_after"] = l.after.dof;
  j["stiffening"] = l.stiffening;
  j["words"] = l.words;
  return j;
}

std::string law_term_source(const LawDiscovery& l, const std::string& name, const std::string& source)
{
  std::string b;
  for (std::size_t k = 0; k < l.coefficients.size(); ++k)
    b += fmt::format("{}{}", k ? ", " : "", l.coefficients[k]);
  const std::string q = "q_" + name;
  return fmt::format(R"PY(# SPDX-License-Identifier: LGPL-3.0-or-later
"""{name}: a tissue law found by `breastsim diagnose` on {source}:
{words}.

    E = int_B q sum_k b_k f_k(F) dV,
    f = ((I1b - 3)^2, (I1b - 3)^3, I2b - 3),  b = ({b}) Pa,

added to the tissue's eq. (5); q = 1 is the law as found, q = 0 eq. (5)
alone. To use it: copy this file into forms/ and add "{name}" to
forms/registry.py.
"""
from common import Constant, F, J, candidate, domain, dx, param, tr

NAME = "{name}"
DEFAULT_ON = False
{q} = Constant(domain)

PARAMETERS = {{
    "{q}": param("{name}.strength", "1", 1.0, 0.0, 10.0,
                 "strength q of the found law's features (1: as found, 0: eq. (5) alone)"),
}}
CANDIDATE = candidate("{name}.strength", "1", 1.0, "the tissue law found beyond eq. (5)",
                      sets={{"{q}": "q"}}, default=False)

COEFFICIENTS = [{b}]
C = F.T * F
I1b = J ** (-2.0 / 3.0) * tr(C)
I2b = J ** (-4.0 / 3.0) * (tr(C) ** 2 - tr(C * C)) / 2
FEATURES = [(I1b - 3) ** 2, (I1b - 3) ** 3, I2b - 3]
ENERGY = {q} * sum(b * f for b, f in zip(COEFFICIENTS, FEATURES)) * dx
)PY",
                     fmt::arg("name", name), fmt::arg("source", source), fmt::arg("words", l.words),
                     fmt::arg("b", b), fmt::arg("q", q));
}
} // namespace breastsim::diagnosis
