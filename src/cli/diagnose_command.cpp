// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim diagnose RECORDING.json --case CASE.toml`: locate where the
// simulation and a 3D recording differ, name the physics that was left out,
// model it, refit and show the fit improve (docs/DIAGNOSE.md).
#include "candidates.hpp"
#include "case_groups.hpp"
#include "command.hpp"
#include "diagnosis_output.hpp"
#include "fit_parameters.hpp"
#include "log.hpp"
#include "output_options.hpp"
#include "overrides.hpp"
#include "recording.hpp"
#include "strings.hpp"
#include "viewer.hpp"
#include <iostream>
#include <memory>

namespace breastsim::cli
{
namespace
{
/// The diagnosis mesh and its check mesh (docs/DIAGNOSE.md, steps 1-2).
void add_mesh_options(CLI::App* app, diagnosis::DiagnoseOptions& d)
{
  d.order = 2;
  d.mesh_size = 0.012;
  app->add_option("--order", d.order,
                  "element order of the diagnosis mesh (0: the case's; docs/DIAGNOSE.md)")
      ->capture_default_str();
  app->add_option("--mesh-size", d.mesh_size,
                  "mesh size of the diagnosis mesh [m] (0: the case's; a mesh file keeps its mesh)")
      ->capture_default_str();
  app->add_option("--mesh-ratio", d.mesh_ratio,
                  "numerical noise floor: the fitted model is also solved on a mesh this many "
                  "times finer (<= 1: off)")
      ->capture_default_str();
}
} // namespace

Command add_diagnose_command(CLI::App& root)
{
  struct Options
  {
    std::string recording, case_file, candidates;
    OutputOption out;
    std::vector<std::string> sets;
    diagnosis::DiagnoseOptions d;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand("diagnose", "find the physics a model leaves out: where the "
                                              "simulation and a 3D recording differ, which "
                                              "candidate term explains it, refit, improvement");
  app->add_option("recording", o->recording, "3D surface recording (JSON, breastsim-recording/1; "
                                             "README)")->required();
  app->add_option("--case", o->case_file, "the current model (TOML): terms on, known parameters, "
                                          "mesh (default: every default key)");
  app->add_option("--set", o->sets, "override a case key (repeatable)");
  add_output_option(app, o->out, "output folder (default results/diagnosis); replaced on success");
  app->add_option("--fit", o->d.fit, "current-model parameters refitted (" + calibration::fit_alias_names()
                                         + ")")->capture_default_str();
  const std::string left_out = diagnosis::candidates_not_default();
  app->add_option("--candidates", o->candidates, "comma-separated subset of the candidate library ("
                                                     + diagnosis::candidate_names()
                                                     + "; default: every candidate whose term is off"
                                                     + (left_out.empty() ? std::string() : ", but " + left_out)
                                                     + ")");
  app->add_option("--alpha", o->d.alpha, "false-discovery level of a round")->capture_default_str();
  app->add_option("--max-rounds", o->d.max_rounds, "physics found at most: rounds of discovery, not counting a round that finds a regional variation of a found physics (skin_upper_pole)")->capture_default_str();
  app->add_option("--refits", o->d.refits, "significant candidates refitted per round (the largest "
                                           "likelihood ratio wins)")->capture_default_str();
  app->add_option("--min-score-fraction", o->d.min_score_fraction,
                  "refit a significant candidate only if its score reaches this fraction of its "
                  "critical value with the mesh allowance (0: refit every one)")->capture_default_str();
  add_mesh_options(app, o->d);
  app->add_option("--min-effect", o->d.min_effect, "an accepted term must change the surface by "
                                                   "this fraction of the noise (RMS over all "
                                                   "points), also at its interval's end (0: off)")->capture_default_str();
  app->add_option("--min-misfit-share", o->d.min_misfit_share,
                  "an accepted term must explain this fraction of the misfit (chi2 - dof) of the "
                  "model before it (0: off)")->capture_default_str();
  app->add_option("--min-misfit-share-later", o->d.min_misfit_share_later,
                  "the same for a term tested after another was found (0: off)")->capture_default_str();
  app->add_option("--min-separation-z", o->d.min_separation_z,
                  "an accepted term is named only if it beats every other candidate that holds "
                  "the rules by this z (Vuong's test on the margins; 0: off)")->capture_default_str();
  app->add_option("--jackknife-patches", o->d.jackknife_patches,
                  "model-form uncertainty of the found values: the patch jackknife splits each "
                  "posture's points into N x N patches (0: only the posture jackknife)")
      ->capture_default_str();
  app->add_option("--refinement-order", o->d.refinement_order,
                  "an accepted term's LR must pass on the finer mesh and extrapolated to the "
                  "continuum with this order (0: off)")->capture_default_str();
  app->add_flag("!--no-field", o->d.discover_field,
                "do not model a misfit the candidates leave as a stiffness field");
  app->add_flag("!--no-law", o->d.discover_law,
                "do not model a misfit the candidates leave by the tissue law's invariant features");
  app->add_flag("!--no-held-out", o->d.held_out_check,
                "do not require a gain in the prediction of held-out postures");
  app->add_option("--ranks-per-case", o->d.ranks_per_case,
                  "MPI ranks per forward solve: the ranks split into groups of this many, which "
                  "solve the postures of every evaluation side by side (0: all ranks on each "
                  "solve; must divide the number of ranks)")
      ->capture_default_str();
  return {app, [o]()
          {
            const Config c = load_case(o->case_file, o->sets);
            const auto rec = calibration::read_recording(o->recording);
            o->d.candidates = split_list(o->candidates);
            CaseGroups::check(MPI_COMM_WORLD, o->d.ranks_per_case, "--ranks-per-case");
            if (OutputOptions::from(c).pictures_on())
              check_picture_tools(MPI_COMM_WORLD); // fail before the solves, not after
            const auto out = claim_output(o->out, "results/diagnosis", {o->recording, o->case_file});
            const std::string report = diagnosis::run_diagnosis(rec, c, o->d, out, MPI_COMM_WORLD);
            if (log::is_root())
              std::cout << report << pictures_hint(c, out.path());
            return 0;
          }};
}
} // namespace breastsim::cli
