// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The data of a missing-physics diagnosis (diagnose.hpp): its options, the
// fits, regions, candidate scores and rounds, and the result.
#include "config.hpp"
#include "least_squares.hpp"
#include "recording.hpp"
#include "uncertainty.hpp"
#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim::diagnosis
{
using calibration::Point;
using calibration::Recording;
using calibration::LsqOptions;
using calibration::Matrix;
using calibration::Uncertainty;

struct DiagnoseOptions
{
  std::string fit = "mu";              ///< current-model parameters refitted (--fit names)
  std::vector<std::string> candidates; ///< library subset to test ("": every applicable one)
  double alpha = 1e-3;                 ///< false-discovery level of one round (all candidates)
  int max_rounds = 2; ///< physics found at most (an extension does not count)
  /// The diagnosis discretisation of the parametric cap: element order and
  /// mesh size the fits are made on (0: the case's). `breastsim diagnose`
  /// defaults to P2 at 12 mm (docs/DIAGNOSE.md); the written case keeps the
  /// case's own order and mesh size.
  int order = 0;
  double mesh_size = 0;
  bool discover = true;                ///< false: only fit the current model (calibration)
  /// Field discovery after the rounds when a misfit remains (field_discovery.hpp).
  bool discover_field = true;
  /// Law discovery after the rounds when a misfit remains (law_discovery.hpp).
  bool discover_law = true;
  int refits = 2;                      ///< significant candidates refitted per round (best LR wins)
  int neighbours = 12;                 ///< k of the neighbourhood means (localisation)
  double region_z = 4.0;               ///< |neighbourhood z| that marks a point as systematic
  /// Numerical noise floor: the fitted current model is also solved on a
  /// mesh `mesh_ratio` times finer; the mean square change of the distances
  /// and of the landmarks, e_h^2, is added to the noise,
  ///   sigma_eff^2 = sigma^2 + e_h^2,
  /// so that the discretisation error of the diagnosis mesh is not mistaken
  /// for missing physics. mesh_ratio <= 1: off (sigma_eff = sigma). A
  /// point's e_h,i is the RMS change over itself and its `neighbours`
  /// nearest points, so that the few points where the diagnosis mesh is poor
  /// (a crease at the inframammary fold: up to 0.7 mm against a posture RMS
  /// of 0.05 mm, on an independent-truth control) are not averaged away.
  double mesh_ratio = 1.5;
  /// Practical significance: an accepted term must change the model surface
  /// by at least this fraction of the noise sigma (RMS over all points), also
  /// at the end of its 95 % interval nearest the null (0: off).
  double min_effect = 0.1;
  /// Refinement check: an accepted term's LR must stay above its critical
  /// value with the mesh allowance on the mesh `mesh_ratio` times finer and
  /// extrapolated to the continuum (evidence.hpp, continuum_lr) with this
  /// order (0: off).
  double refinement_order = 1.5;
  /// Held-out postures: an accepted term must improve the linearised
  /// prediction of the postures it was not fitted on (sum of chi2 gains > 0).
  bool held_out_check = true;
  /// Model-form share: an accepted term must explain at least this fraction
  /// of the systematic misfit it is tested against, LR >= share (chi2 - dof)
  /// of the model before it (0: off). The misfit left by the model so far
  /// estimates its model-form error (the shape error of the terms it has, a
  /// physics no candidate has, the mesh's error beyond the noise floor); a
  /// term that removes only a small part of it stands in for that error.
  double min_misfit_share = 0.3;
  /// The same for a term tested after another was found: the misfit left
  /// then holds the found term's own shape error, which other candidates
  /// imitate; a further term must explain at least this fraction of it.
  double min_misfit_share_later = 0.5;
  /// Refit screen: a candidate is refitted only if its score S (the
  /// linearised LR) reaches this fraction of its critical value with the
  /// mesh allowance; below it the refit could not pass (refits' LR were
  /// within 0.85-1.15 of their score on the independent truth).
  double min_score_fraction = 0.5;
  /// Separation: an accepted term is named only if its margin over its
  /// critical value beats every other refitted candidate that holds the
  /// rules by this many standard deviations of Vuong's test (separation.hpp;
  /// 0: off); otherwise the hidden physics lies between the candidates.
  double min_separation_z = 1.96;
  /// Model-form uncertainty of the found values (model_form.hpp): the patch
  /// jackknife splits each posture's points into b x b patches (0: only
  /// the posture jackknife).
  int jackknife_patches = 3;
  /// MPI ranks per forward solve: the postures of every evaluation are
  /// solved by groups of this many ranks side by side (0: all ranks).
  int ranks_per_case = 0;
  LsqOptions lsq;
};

/// Throws InputError naming the option, its value and the allowed range
/// unless every option of `o` is in range (the candidate names known).
void check(const DiagnoseOptions& o);

/// The evidence for or against one refitted candidate (evidence.hpp).
struct Evidence
{
  std::string candidate;
  double lr = 0, critical = 0;                 ///< LR and its critical value (with the mesh allowance)
  std::vector<double> effect_rms_mm, effect_max_mm; ///< per posture
  double effect_rms_mm_all = 0;                ///< RMS over all points
  double effect_rms_mm_largest = 0;            ///< largest per-posture RMS (the posture it changes most)
  double effect_at_null_edge_mm = 0;           ///< the judged effect at the interval end nearest q = 0
  std::vector<double> held_out_gain;           ///< per posture: chi2_k without - with the term
  bool held_out_solved = false;                ///< held_out_gain solved (else linearised)
  std::vector<double> held_out_gain_linearised; ///< the linearised gains (held_out_solved)
  double misfit_before = 0;                    ///< chi2 - dof of the model before the term
  int terms_before = 0;                        ///< terms found before this one
  bool refinement_checked = false;
  double lr_fine = 0, lr_continuum = 0;        ///< refinement check (refinement_checked)
  double critical_fine = 0, critical_continuum = 0; ///< their critical values (refinement_critical)
  std::vector<std::string> failed;             ///< reasons for rejection (empty: holds every rule checked)
  bool accepted = false;                       ///< the round's accepted candidate
};

/// A region of systematic residual on one posture's surface.
struct Region
{
  std::string posture;
  std::string where;                   ///< plain-words location
  int points = 0;
  Point centroid{};                    ///< [m]
  double mean_residual = 0;            ///< mean normal distance [m] (+: recording outside the model)
  double max_residual = 0;             ///< largest |distance| [m]
  double z = 0;                        ///< sum of whitened residuals / sqrt(points)
};

/// One fitted model: parameters, residuals, goodness of fit.
struct FitState
{
  std::vector<std::string> names, units;
  std::vector<double> values;                      ///< fitted parameters [unit]
  Uncertainty uncertainty;
  std::vector<std::vector<double>> distances;      ///< per posture, per point [m]
  std::vector<std::array<double, 3>> nipple_error; ///< per posture, model - landmark [m] (NaN: none)
  std::vector<double> r;                           ///< whitened residuals (points, then landmarks)
  Matrix J;                                        ///< dr/d ln p
  double chi2 = 0;
  int dof = 0;
  double gof_z = 0;                                ///< (chi2 - dof) / sqrt(2 dof)
  double gof_p = 1;                                ///< P(chi2 >= observed | noise only), normal approx.
  std::vector<double> rms, max_abs;                ///< per posture [m]
  int evaluations = 0;
  Config config;                                   ///< the fitted case
};

struct CandidateScore
{
  std::string name;
  double score = 0;     ///< S (0 when the data pull q below 0)
  double p_value = 1;   ///< one-sided, P(N(0,1) > U / sqrt(I))
  double estimate = 0;  ///< linearised q* = U / I [candidate unit]
  /// LR the diagnosis mesh's own discretisation error could give this
  /// candidate: kappa^2 max(0, -j^T P e)^2 / I, e = r_h - r_{h/r}, kappa = 1/(1 - 1/r);
  /// added to the critical value.
  double mesh_allowance = 0;
};

/// A candidate that fits about as well as the accepted one (separation.hpp).
struct Rival
{
  std::string candidate;
  double z = 0;            ///< Vuong's z of the accepted candidate over this one
  double margin_diff = 0;  ///< (LR - critical) accepted - this one
};

/// An accepted term that is not named: its rivals fit as well.
struct Undecided
{
  std::string used;            ///< the term the fitted model carries
  std::vector<Rival> rivals;   ///< the candidates it cannot be told from
};

struct Round
{
  FitState before;
  std::vector<Region> regions;
  std::vector<CandidateScore> scores; ///< sorted, best first
  std::vector<std::pair<std::string, double>> refits; ///< candidates refitted, their LR
  std::vector<std::string> screened_out; ///< significant, not refitted: S below the refit screen
  double screen_fraction = 0;            ///< the refit screen's fraction of the critical value
  std::string tested;                 ///< best refitted candidate ("" = none significant)
  FitState after;                     ///< valid if !tested.empty()
  double lr = 0, critical = 0;        ///< LR of `tested`; critical value of the level
  double critical_used = 0;           ///< critical + the tested candidate's mesh allowance
  bool accepted = false;
  std::vector<Evidence> evidence;     ///< every refitted candidate, in refit order
  std::vector<Rival> rivals;          ///< accepted: other candidates within the separation level
};

struct FieldDiscovery;
struct LawDiscovery;
struct Diagnosis
{
  std::vector<Round> rounds;
  /// The stiffness field tried after the rounds (field_discovery.hpp; null: not run).
  std::shared_ptr<const FieldDiscovery> field;
  /// The tissue law tried after the rounds (law_discovery.hpp; null: not run).
  std::shared_ptr<const LawDiscovery> law;
  FitState final_fit;                 ///< after a discovery: refitted on the finer mesh
  std::vector<double> se_numerical;   ///< numerical part of the SE of ln p (final_fit)
  std::vector<double> se_statistical; ///< statistical SE of ln p of the final fit (noise, chi2/dof)
  std::vector<double> se_model_form;  ///< model-form part of the SE of ln p (model_form.hpp)
  std::vector<double> se_posture_jackknife; ///< its posture jackknife
  std::vector<double> se_patch_jackknife;   ///< its patch jackknife
  /// Skin surface documents (surface_export.hpp) of the final model per
  /// posture, on the diagnosis mesh (rank 0).
  std::vector<nlohmann::json> surfaces;
  std::vector<std::string> discovered;
  std::vector<Undecided> undecided;   ///< terms in the fit that the data cannot name
  std::string verdict;                ///< plain words
  bool fit_only = false;              ///< no candidate was tested (DiagnoseOptions::discover)
  double noise_sigma = 0;
  std::vector<double> mesh_error;     ///< e_h per posture (distances) [m]
  std::vector<double> sigma_eff;      ///< sqrt(sigma^2 + e_h^2) per posture [m]
  std::vector<double> local_floor_max; ///< largest e_h,i per posture [m] (empty without a noise floor)
  /// Postures the fitted current model cannot be solved in on the finer
  /// mesh: their e_h is the largest of the others', the refinement checks
  /// leave them out, and the final values are the diagnosis mesh's unless
  /// they rejoin (rejoined_on_finer).
  std::vector<std::string> unsolved_on_finer;
  /// Postures solved on the finer mesh at the noise floor that a later model
  /// (a refinement check's, the final refit's) cannot be solved in there:
  /// left out of the finer mesh's solves from then on, as above (the step
  /// that met it restarts without them).
  std::vector<std::string> lost_on_finer;
  /// Postures of the two lists above that the model solves on the finer
  /// mesh again once a term is found: back in the finer mesh's solves.
  std::vector<std::string> rejoined_on_finer;
  /// The final values are the finer mesh's (false: some posture is left out
  /// of it at the end, and they are the diagnosis mesh's).
  bool final_on_finer_mesh = true;
  int order = 1;                      ///< element order of the diagnosis mesh
  double mesh_size = 0;               ///< its mesh size [m] (0: a user's mesh file)
  double mesh_ratio = 0;              ///< the finer check mesh: mesh_size / mesh_ratio (<= 1: none)
  int posture_solves = 0;
  double seconds = 0;
};
} // namespace breastsim::diagnosis
