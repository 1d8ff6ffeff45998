// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim converge CASE.toml --levels N [--order 1,2] [--quantity ...]
// [--stage preop|surgery] [--mms [--mms-meshes nested|split|remesh]
// [--mms-length L --mms-amplitude A --mms-kappa K]]`:
// mesh-convergence study of the case's standing posture, pre- or
// post-operative (observed order,
// Richardson extrapolation, GCI of the finest level) or, with --mms, the
// manufactured-solution verification (L2/H1 error orders). docs/CONVERGENCE.md.
#include "config.hpp"
#include "case_options.hpp"
#include "convergence.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "strings.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace breastsim::cli
{

namespace
{
/// --mms-length, --mms-amplitude, --mms-kappa: u_ex of the nearly
/// incompressible MMS (verification/mms_mixed.hpp).
void add_incompressible_mms_options(CLI::App* app, IncompressibleMmsSetup& setup)
{
  app->add_option("--mms-length", setup.length,
                  "with --mms and tissue.formulation = mixed: length scale L [m] of u_ex = "
                  "curl psi + kappa (mu / lambda) grad phi (0.001 .. 10)")
      ->check(CLI::Range(1e-3, 10.0))
      ->capture_default_str();
  app->add_option("--mms-amplitude", setup.amplitude,
                  "with --mms and tissue.formulation = mixed: amplitude A [m] of u_ex "
                  "(1e-8 .. 0.01; |grad u_ex| ~ A / L)")
      ->check(CLI::Range(1e-8, 1e-2))
      ->capture_default_str();
  app->add_option("--mms-kappa", setup.kappa,
                  "with --mms and tissue.formulation = mixed: weight kappa of u_ex's volumetric "
                  "part, pressure ~ kappa mu A / L (0 .. 100; 0: divergence-free)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
}

/// The u_ex options belong to the mixed formulation's MMS: InputError otherwise.
void check_incompressible_mms_options(const CLI::App& app, bool incompressible_mms)
{
  for (const char* option : {"--mms-length", "--mms-amplitude", "--mms-kappa"})
    if (app.count(option) && !incompressible_mms)
      throw InputError(fmt::format("{} = {}: only with --mms and tissue.formulation = \"mixed\"",
                                   option, app.get_option(option)->as<std::string>()));
}
} // namespace

Command add_converge_command(CLI::App& root)
{
  struct Options
  {
    std::string case_file, orders = "1", quantities = "nipple_z,projection,energy";
    std::string mms_meshes = "nested", stage = "preop", refine = "gmsh";
    std::vector<std::string> sets;
    OutputOption out;
    int levels = 3;
    bool mms = false;
    IncompressibleMmsSetup incompressible;
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand(
      "converge", "mesh-convergence study: observed order, Richardson value and GCI per quantity "
                  "(or the MMS verification with --mms)");
  app->add_option("case", o->case_file, "case file (TOML, SI units; see `breastsim keys`)")->required();
  app->add_option("--levels", o->levels, "number of meshes: geometry.refinements = 0 .. N-1 (3..5)")
      ->check(CLI::Range(3, 5));
  app->add_option("--order", o->orders, "element orders, comma separated (1, 2)");
  app->add_option("--quantity", o->quantities,
                  "quantities, comma separated: nipple_x, nipple_y, nipple_z, projection, z_min, "
                  "z_max, base_perimeter, volume, energy");
  app->add_option("--set", o->sets, "override a case key (repeatable)")->allow_extra_args(false);
  add_output_option(app, o->out,
                    "output folder (default results/<case.name>-convergence); replaced on success");
  app->add_flag("--mms", o->mms,
                "manufactured-solution problem instead of the case's posture (the case's "
                "material, geometry and mesh_size; gravity off)");
  app->add_option("--stage", o->stage,
                  "preop: the standing posture of the case's cap; surgery: the case's incision, "
                  "sutures and reset, then the post-operative standing posture (adds the "
                  "quantities resected_volume, max_gap)")
      ->check(CLI::IsMember({"preop", "surgery"}));
  app->add_option("--refine", o->refine,
                  "gmsh: gmsh's splitting (geometry.refinements, default); red: red refinement "
                  "of the level-0 mesh, new skin nodes snapped to the cap (preop stage only)")
      ->check(CLI::IsMember({"gmsh", "red"}));
  app->add_option("--mms-meshes", o->mms_meshes,
                  "MMS mesh family: nested (red refinement of the gmsh mesh, default), split "
                  "(gmsh splitting, boundary snapped to the sphere), remesh (gmsh at "
                  "mesh_size / 2^l)");
  add_incompressible_mms_options(app, o->incompressible);
  return {app, [o, app]()
          {
            Config c = load_case(o->case_file, o->sets);
            const bool incompressible_mms =
                o->mms && CaseOptions::from(c).formulation == TissueFormulation::mixed;
            check_incompressible_mms_options(*app, incompressible_mms);
            ConvergeRequest r;
            r.levels = o->levels;
            r.orders = parse_orders(o->orders);
            r.quantities = split_list(o->quantities);
            r.mms = o->mms;
            r.mms_meshes = parse_mms_meshes(o->mms_meshes);
            r.mms_incompressible = o->incompressible;
            r.stage = o->stage == "surgery" ? ConvergeStage::surgery : ConvergeStage::preop;
            r.refine = o->refine == "red" ? ConvergeRefinement::red : ConvergeRefinement::gmsh;
            const auto out = claim_output(o->out, "results/" + CaseOptions::from(c).name + "-convergence",
                                          {o->case_file});
            const ConvergeReport report = run_convergence(c, r, out, MPI_COMM_WORLD);
            const bool png = report.plotted;
            if (log::is_root())
            {
              std::cout << report.table;
              std::cout << "results written to " << out.path().string() << "/ (convergence.json, convergence.txt"
                        << (png ? ", convergence.png" : "; no plot: python3/matplotlib failed")
                        << ")\n";
            }
            return 0;
          }};
}
} // namespace breastsim::cli
