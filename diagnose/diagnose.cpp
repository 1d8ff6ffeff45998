// SPDX-License-Identifier: LGPL-3.0-or-later
// The rounds of a diagnosis (diagnose.hpp): fit, noise floor, then per round
// WHERE (residual_regions.cpp), WHAT (candidate_scores.cpp), MODEL IT (the
// refits, here) and the acceptance test; at the end the finer-mesh refit of
// what was found (mesh_error.cpp).
#include "diagnose.hpp"
#include "diagnosis_case.hpp"
#include "candidate_scores.hpp"
#include "errors.hpp"
#include "evidence.hpp"
#include "field_discovery.hpp"
#include "law_discovery.hpp"
#include "missing_physics.hpp"
#include "fit_parameters.hpp"
#include "fit_state.hpp"
#include "geometry_options.hpp"
#include "linearised_refit.hpp"
#include "log.hpp"
#include "mesh_error.hpp"
#include "model_form.hpp"
#include "residual_regions.hpp"
#include "separation.hpp"
#include "solved_held_out.hpp"
#include "timer.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <optional>
#include <utility>

namespace breastsim::diagnosis
{
namespace
{
/// The value of `step()`, a std::optional that is empty when a posture was
/// newly left out of the finer mesh (Search::on_finer): the step is then
/// made again over the other postures (at most once per posture: on_finer
/// throws SolveError when none is left).
template <typename Step>
auto retry_without_lost(Step&& step)
{
  for (;;)
    if (auto value = step())
      return std::move(*value);
}

/// One diagnosis in progress: the model found so far and its fit.
struct Search
{
  Search(const Recording& r, const Config& c, const DiagnoseOptions& opt, MPI_Comm comm)
      : rec(r), o(opt), groups(comm, opt.ranks_per_case, "--ranks-per-case"),
        ev(r, groups.comm(), &groups), current(with_known(c, r, opt)), frees(frees_from_fit(o.fit, current))
  {
    if (o.mesh_ratio > 1)
    {
      fine_ev = std::make_unique<PointEvaluator>(r, groups.comm(), &groups);
      kappa = 1.0 / (1.0 - 1.0 / o.mesh_ratio);
    }
  }

  const Recording& rec;
  const DiagnoseOptions& o;
  CaseGroups groups;   ///< the postures solved side by side (--ranks-per-case)
  PointEvaluator ev;   ///< on this rank's group
  std::unique_ptr<PointEvaluator> fine_ev; ///< the finer mesh of the noise floor (mesh_ratio > 1)
  double kappa = 0;                        ///< Richardson factor 1/(1 - 1/r)
  Config current;                          ///< the model, with the terms found so far
  std::vector<Free> frees;                 ///< its free parameters
  FitState state;                          ///< its fit
  std::optional<SolvedChi2> held_out_current; ///< its solved held-out chi2, once needed
  /// Its fit on the finer mesh, once a refinement check has made one: the
  /// check's refit of the current model, or of the candidate it accepted,
  /// which then is the current model. Reused by later checks and by step 9.
  std::unique_ptr<FitState> fine_state;
  int found = 0;                           ///< terms found so far

  /// Postures solved on the finer mesh at the noise floor that a later
  /// model fails in there (Diagnosis::lost_on_finer).
  std::vector<std::string> lost_on_finer;

  /// Case `c` on the finer mesh, or none: a posture failing there for the
  /// first time is left out of every later solve on it, the current model's
  /// fit there (which holds it) is dropped, and the step that asked starts
  /// again over the other postures (retry_without_lost).
  std::optional<PointEvaluation> on_finer(const Config& c)
  {
    PointEvaluation e;
    if (note_lost(fine_ev->leave_out_failures(c, e)))
      return std::nullopt;
    return e;
  }
  /// Record postures newly left out of the finer mesh and drop the current
  /// model's fit there; true if there were any. Throws SolveError when no
  /// posture is left.
  bool note_lost(const std::vector<std::size_t>& lost)
  {
    for (std::size_t p : lost)
    {
      lost_on_finer.push_back(rec.postures[p].name);
      log::warn("posture '{}' cannot be solved on the finer mesh any more: left out of its "
                "solves from now on", rec.postures[p].name);
    }
    bool any = false;
    for (std::size_t p = 0; p < rec.postures.size(); ++p)
      any = any || !fine_ev->excluded(p);
    if (!any)
      throw SolveError(fmt::format("no posture can be solved on the mesh {:g} times finer any more, "
                                   "so nothing can be checked on it (--mesh-ratio 1 turns the "
                                   "checks off)", o.mesh_ratio));
    if (!lost.empty())
      fine_state.reset();
    return !lost.empty();
  }
  /// Some posture cannot be solved on the finer mesh (mesh_error.hpp).
  bool finer_leaves_out() const
  {
    for (std::size_t p = 0; fine_ev && p < rec.postures.size(); ++p)
      if (fine_ev->excluded(p))
        return true;
    return false;
  }
  /// chi2 of fit `f` over the postures the finer mesh solves.
  double chi2_on_finer_postures(const FitState& f) const
  {
    const auto rows = rows_by_posture(f, rec);
    double chi2 = 0;
    for (std::size_t p = 0; p < rows.size(); ++p)
      for (std::size_t i : rows[p])
        chi2 += fine_ev->excluded(p) ? 0.0 : f.r[i] * f.r[i];
    return chi2;
  }
};

/// Steps 1-2: fit the current model; with a finer mesh, the noise floor and
/// the fit again with sigma_eff.
void fit_current_model(Search& s, Diagnosis& d)
{
  s.state = fit(s.ev, s.current, s.frees, start_values(s.frees), s.o.lsq, "fit of the current model");
  if (!s.fine_ev)
    return;
  const auto sigma = noise_floor(s.ev, *s.fine_ev, s.rec, s.state, s.o, d);
  s.ev.set_sigma(sigma);
  s.fine_ev->set_sigma(sigma);
  s.state = fit(s.ev, s.current, s.frees, log_values(s.state), s.o.lsq, "fit of the current model");
}

/// Step 5: score every applicable candidate at its null value, with the share
/// of the mesh error e = r_h - r_{h/r} along its direction; sorted, best
/// first. Returns the number of candidates tested.
std::size_t score_candidates(Search& s, Round& rd)
{
  std::vector<double> mesh_e;
  if (s.fine_ev)
  {
    const Config fine = finer(s.state.config, s.o.mesh_ratio);
    const PointEvaluation ef = retry_without_lost([&] { return s.on_finer(fine); });
    for (std::size_t i = 0; i < s.state.r.size(); ++i)
      mesh_e.push_back(s.state.r[i] - ef.r[i]);
    const auto rows = rows_by_posture(s.state, s.rec);
    for (std::size_t p = 0; p < rows.size(); ++p)
      for (std::size_t i : rows[p])
        mesh_e[i] *= ef.solved[p] ? 1.0 : 0.0; // unknown there: no allowance from it
  }
  const auto& wanted = s.o.candidates;
  std::vector<const Candidate*> tested;
  for (const auto& c : candidate_library())
    if (c.applicable(s.state.config) && is_wanted(c, wanted))
      tested.push_back(&c);
  for (const Candidate* c : tested)
    rd.scores.push_back(
        score_from_probe(*c, s.state, probe_residuals(s.ev, *c, s.state), mesh_e, s.kappa));
  std::sort(rd.scores.begin(), rd.scores.end(),
            [](const auto& a, const auto& b) { return a.score > b.score; });
  return tested.size();
}

/// The evidence of a refit that needs no further solve: LR, effect in mm,
/// interval edge, held-out postures; judged without the refinement check.
Evidence cheap_evidence(Search& s, const Candidate& cand, const std::vector<Free>& frees,
                        const FitState& after, double lr, double critical)
{
  Evidence e;
  e.candidate = cand.name;
  e.lr = lr;
  e.critical = critical;
  e.misfit_before = s.state.chi2 - s.state.dof;
  e.terms_before = s.found;
  effect_size(s.state, after, e);
  e.effect_at_null_edge_mm = effect_at_interval_edge(after, cand.parameter, e.effect_rms_mm_all);
  const auto without = held_out_chi2(s.state, s.rec), with = held_out_chi2(after, s.rec);
  for (std::size_t k = 0; k < without.size() && k < with.size(); ++k)
    e.held_out_gain.push_back(without[k] - with[k]);
  judge(e, s.o, s.rec.noise_sigma);
  if (held_out_refusal(e, s.o)) // a refusal stands on solved predictions (solved_held_out.hpp)
  {
    if (!s.held_out_current)
      s.held_out_current = solved_held_out_chi2(s.ev, {s.current, s.frees, s.state}, s.rec);
    set_solved_gains(*s.held_out_current, solved_held_out_chi2(s.ev, {s.current, frees, after}, s.rec), e);
    judge(e, s.o, s.rec.noise_sigma);
  }
  return e;
}

Evidence& evidence_of(Round& rd, const std::string& name)
{
  return *std::find_if(rd.evidence.begin(), rd.evidence.end(),
                       [&](const Evidence& e) { return e.candidate == name; });
}

/// The refinement check of the round's best: the current model and the model
/// with the candidate refitted on the finer mesh (one Gauss-Newton step from
/// the diagnosis mesh's fits: the optimum moves little); their LR there and
/// extrapolated to the continuum (evidence.hpp). Returns the candidate's fit
/// on the finer mesh.
std::unique_ptr<FitState> check_refinement(Search& s, Round& rd, const std::vector<Free>& trial)
{
  Evidence& e = evidence_of(rd, rd.tested);
  const Config fine_base = finer(s.current, s.o.mesh_ratio);
  const Evaluate on_fine = [&](const Config& c) { return s.on_finer(c); };
  auto with = retry_without_lost([&]() -> std::optional<std::unique_ptr<FitState>> {
    if (!s.fine_state)
    {
      auto current = gauss_newton_refit(on_fine, fine_base, s.frees, s.state,
                                        "refinement check: current model on the finer mesh");
      if (!current)
        return std::nullopt;
      s.fine_state = std::make_unique<FitState>(std::move(*current));
    }
    auto refit = gauss_newton_refit(on_fine, fine_base, trial, rd.after,
                                    "refinement check: with " + e.candidate);
    if (!refit)
      return std::nullopt;
    return std::make_unique<FitState>(std::move(*refit));
  });
  const FitState& without = *s.fine_state;
  e.refinement_checked = true;
  e.lr_fine = without.chi2 - with->chi2;
  // Extrapolated from the LR on the same postures on both meshes.
  const double lr_h = s.finer_leaves_out()
                          ? s.chi2_on_finer_postures(s.state) - s.chi2_on_finer_postures(rd.after)
                          : e.lr;
  e.lr_continuum = continuum_lr(lr_h, e.lr_fine, s.o.mesh_ratio, s.o.refinement_order);
  e.critical_fine = e.critical_continuum = refinement_critical(rd.critical, e.critical - rd.critical);
  log::info("candidate '{}': LR {:.1f} on the finer mesh, {:.1f} in the continuum", e.candidate,
            e.lr_fine, e.lr_continuum);
  judge(e, s.o, s.rec.noise_sigma);
  return with;
}

/// A refitted candidate: its free parameters and fit.
struct Refit
{
  std::string name;
  std::vector<Free> frees;
  FitState after;
  double lr = 0, critical = 0;
};

/// Step 6: refit the (at most o.refits) best-scoring candidates with a
/// p-value below `level` whose score passes the refit screen, each with its
/// evidence (cheap_evidence) in rd.
std::vector<Refit> refit_candidates(Search& s, Round& rd, double level)
{
  std::vector<Refit> refits;
  for (std::size_t k = 0; k < rd.scores.size() && k < static_cast<std::size_t>(s.o.refits); ++k)
  {
    const CandidateScore& sc = rd.scores[k];
    if (sc.p_value >= level)
      break;
    if (sc.score < s.o.min_score_fraction * (rd.critical + sc.mesh_allowance))
    {
      rd.screened_out.push_back(sc.name);
      rd.screen_fraction = s.o.min_score_fraction;
      continue;
    }
    const Candidate& cand = candidate(sc.name);
    Refit r{cand.name, s.frees, {}, 0, rd.critical + sc.mesh_allowance};
    r.frees.push_back(free_candidate(cand));
    auto y = log_values(s.state);
    y.push_back(std::log(std::clamp(sc.estimate, cand.typical * 1e-3, cand.typical * 1e2)));
    try
    {
      r.after = fit(s.ev, s.current, r.frees, y, s.o.lsq, "refit with " + cand.name);
    }
    catch (const SolveError& err)
    {
      log::warn("candidate '{}': the refit failed ({}); skipped", cand.name, err.what());
      continue;
    }
    r.lr = s.state.chi2 - r.after.chi2;
    log::info("candidate '{}': LR = {:.1f} against the critical {:.1f} (level {:.2g}, mesh-error "
              "allowance {:.1f})",
              cand.name, r.lr, r.critical, level, sc.mesh_allowance);
    rd.refits.push_back({cand.name, r.lr});
    rd.evidence.push_back(cheap_evidence(s, cand, r.frees, r.after, r.lr, r.critical));
    refits.push_back(std::move(r));
  }
  // Largest margin of LR over its critical value first: the score is a
  // local, linearised ranking, the refit is not.
  std::sort(refits.begin(), refits.end(),
            [](const Refit& a, const Refit& b) { return a.lr - a.critical > b.lr - b.critical; });
  return refits;
}

/// The other refits that hold the (cheap) rules and whose margin is within
/// the separation level of the accepted refits[k]'s (separation.hpp).
std::vector<Rival> rivals_of(const Search& s, Round& rd, const std::vector<Refit>& refits, std::size_t k)
{
  std::vector<Rival> out;
  for (std::size_t j = 0; j < refits.size() && s.o.min_separation_z > 0; ++j)
  {
    if (j == k || !evidence_of(rd, refits[j].name).failed.empty())
      continue;
    const double diff = (refits[k].lr - refits[k].critical) - (refits[j].lr - refits[j].critical);
    const double z = separation_z(refits[k].after, refits[j].after, diff);
    log::info("candidate '{}' against '{}': margin difference {:.1f}, separation z = {:.2f}",
              refits[k].name, refits[j].name, diff, z);
    if (z < s.o.min_separation_z)
      out.push_back({refits[j].name, z, diff});
  }
  return out;
}

/// Step 7: the first refit (by margin) whose evidence holds, with the
/// refinement check when it is on; rd.tested/lr/after describe it (or the
/// best refit when none holds). Returns its free parameters and, from the
/// refinement check, its fit on the finer mesh.
std::pair<std::vector<Free>, std::unique_ptr<FitState>> decide(Search& s, Round& rd,
                                                               std::vector<Refit>& refits)
{
  for (std::size_t k = 0; k < refits.size(); ++k)
  {
    Refit& r = refits[k];
    if (k > 0 && !evidence_of(rd, r.name).failed.empty())
      continue;
    rd.tested = r.name;
    rd.lr = r.lr;
    rd.critical_used = r.critical;
    rd.after = r.after;
    if (!evidence_of(rd, r.name).failed.empty())
      continue; // the best by margin fails: try the others that hold
    std::unique_ptr<FitState> fine;
    if (s.fine_ev && s.o.refinement_order > 0)
      fine = check_refinement(s, rd, r.frees);
    if (evidence_of(rd, r.name).failed.empty())
    {
      rd.rivals = rivals_of(s, rd, refits, k);
      return {r.frees, std::move(fine)};
    }
  }
  return {};
}

/// After a found term: the postures left out of the finer mesh are tried
/// there again with the model that has it; those it solves rejoin the finer
/// mesh's solves (the current model's fit there is then made again, over
/// every posture it solves, by the next check or by step 9).
void rejoin_finer(Search& s, Diagnosis& d)
{
  if (!s.fine_ev || !s.finer_leaves_out())
    return;
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < s.rec.postures.size(); ++p)
    if (s.fine_ev->excluded(p))
    {
      out.push_back(p);
      s.fine_ev->include(p);
    }
  PointEvaluation e;
  auto failed = s.fine_ev->leave_out_failures(finer(s.current, s.o.mesh_ratio), e);
  const auto was_out = [&](std::size_t p) { return std::find(out.begin(), out.end(), p) != out.end(); };
  for (std::size_t p : out)
    if (std::find(failed.begin(), failed.end(), p) == failed.end())
    {
      d.rejoined_on_finer.push_back(s.rec.postures[p].name);
      log::info("posture '{}' solves on the finer mesh with '{}': back in its checks",
                s.rec.postures[p].name, d.discovered.back());
      s.fine_state.reset();
    }
  failed.erase(std::remove_if(failed.begin(), failed.end(), was_out), failed.end());
  s.note_lost(failed); // a posture the found term's model fails in for the first time
}

/// One round of discovery (steps 4-7); true if a candidate was accepted
/// (the search then holds the model with it).
bool discovery_round(Search& s, Diagnosis& d)
{
  Round rd;
  rd.before = s.state;
  rd.regions = locate_regions(s.rec, s.state, s.o.neighbours, s.o.region_z);
  if (!s.o.discover)
  {
    d.fit_only = true;
    d.rounds.push_back(rd);
    return false;
  }
  const std::size_t tested = score_candidates(s, rd);
  const double level = s.o.alpha / std::max<std::size_t>(tested, 1);
  rd.critical = boundary_lr_critical(level);
  std::vector<Refit> refits = refit_candidates(s, rd, level);
  auto [trial, fine] = decide(s, rd, refits);
  rd.accepted = !rd.tested.empty() && evidence_of(rd, rd.tested).failed.empty();
  if (rd.accepted)
    evidence_of(rd, rd.tested).accepted = true;
  if (!rd.tested.empty())
    log::info("best refit '{}': LR = {:.1f}: {}", rd.tested, rd.lr,
              rd.accepted ? "accepted" : "rejected");
  d.rounds.push_back(rd);
  if (!rd.accepted)
    return false;
  d.discovered.push_back(rd.tested);
  ++s.found;
  s.frees = trial;
  s.current = rd.after.config; // the candidate term is on from now on
  s.state = rd.after;
  s.held_out_current.reset();
  s.fine_state = std::move(fine); // none (no refinement check): step 9 refits on the finer mesh
  rejoin_finer(s, d);
  return true;
}

/// The final model refitted on the finer mesh: a full fit for a calibration
/// (fit only), else Gauss-Newton steps from the diagnosis mesh's fit.
FitState final_fit_on_finer_mesh(Search& s, bool fit_only)
{
  const Config fine = finer(s.current, s.o.mesh_ratio);
  if (fit_only)
    return fit(*s.fine_ev, fine, s.frees, log_values(s.state), s.o.lsq, "refit on the finer mesh");
  const Evaluate on_fine = [&](const Config& c) { return s.on_finer(c); };
  return retry_without_lost(
      [&] { return gauss_newton_refit(on_fine, fine, s.frees, s.state, "final model on the finer mesh"); });
}
} // namespace

Diagnosis diagnose(const Recording& rec, const Config& current, const DiagnoseOptions& o,
                   MPI_Comm comm)
{
  const Stopwatch stopwatch("diagnose");
  check(o);
  Diagnosis d;
  d.noise_sigma = rec.noise_sigma;
  d.mesh_error.assign(rec.postures.size(), 0.0);
  d.sigma_eff.assign(rec.postures.size(), rec.noise_sigma);
  Search s(rec, current, o, comm);
  fit_current_model(s, d);
  // Step 8: rounds until nothing (more) is significant or o.max_rounds
  // physics are found (an extension does not count).
  bool accepted = true;
  while (accepted && physics_found(d.discovered) < o.max_rounds)
    accepted = discovery_round(s, d);
  construct_missing_physics(s.ev, rec, s.frees, s.state, o, current, d);
  d.final_fit = s.state;
  d.se_statistical = s.state.uncertainty.se_log;
  // Step 9: the numerical uncertainty of the fitted values.
  if (s.fine_ev && !s.frees.empty())
  {
    const FitState f = s.fine_state ? *s.fine_state : final_fit_on_finer_mesh(s, d.fit_only);
    d.se_statistical = f.uncertainty.se_log;
    d.final_on_finer_mesh = !s.finer_leaves_out();
    d.final_fit = with_numerical_uncertainty(s.state, f, o.mesh_ratio, d.final_on_finer_mesh,
                                             d.se_numerical);
  }
  if (s.found > 0)
  {
    estimate_model_form(d.final_fit, rec, o.jackknife_patches, d);
    widen_by_model_form(d.final_fit, d.se_model_form);
  }
  d.surfaces = s.ev.surfaces(d.final_fit.config);
  const HalfCapSpec mesh = HalfCapSpec::from(s.current);
  d.order = mesh.order;
  d.mesh_size = mesh.mesh_file.empty() ? mesh.mesh_size : 0.0;
  d.mesh_ratio = o.mesh_ratio;
  d.final_fit.config = on_users_mesh(d.final_fit.config, current);
  d.lost_on_finer = s.lost_on_finer;
  if (s.fine_ev)
    d.posture_solves += s.fine_ev->posture_solves();
  d.posture_solves += s.ev.posture_solves();
  set_aside_inseparable(d);
  d.seconds = stopwatch.seconds();
  d.verdict = verdict_text(d, rec, o.alpha) + (d.field ? field_verdict(*d.field, s.state) : "")
              + (d.law ? law_verdict(*d.law, s.state) : "");
  return d;
}
} // namespace breastsim::diagnosis
