// `breastsim converge CASE.toml --levels N [--order 1,2] [--quantity ...]
// [--stage preop|surgery] [--mms [--mms-meshes nested|split|remesh]]`:
// mesh-convergence study of the case's standing posture, pre- or
// post-operative (observed order,
// Richardson extrapolation, GCI of the finest level) or, with --mms, the
// manufactured-solution verification (L2/H1 error orders). docs/CONVERGENCE.md.
#include "config.hpp"
#include "convergence.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "mms.hpp"
#include "output.hpp"
#include "command.hpp"
#include "overrides.hpp"
#include <iostream>
#include <memory>
#include <sstream>

namespace breastsim::cli
{
namespace
{
std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
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
  return {app, [o]()
          {
            Config c = load_case(o->case_file, o->sets);
            std::vector<int> orders;
            for (const auto& s : split(o->orders))
            {
              try
              {
                orders.push_back(std::stoi(s));
              }
              catch (const std::exception&)
              {
                throw InputError("--order: not an integer: '" + s + "'");
              }
              if (orders.back() != 1 && orders.back() != 2)
                throw InputError("--order: element order must be 1 or 2, got " + s);
            }
            const auto out = claim_output(o->out, "results/" + c.text("case.name") + "-convergence",
                                          {o->case_file});
            nlohmann::json j;
            j["case"] = c.text("case.name");
            j["levels"] = o->levels;
            j["stage"] = o->mms ? "mms" : o->stage;
            std::string report;
            const MmsMeshes mms_meshes = parse_mms_meshes(o->mms_meshes);
            if (o->mms)
            {
              for (int p : orders)
              {
                auto s = mms_study(c, p, c.number("geometry.mesh_size"), o->levels, MPI_COMM_WORLD,
                                   mms_meshes);
                j["mms"].push_back(to_json(s));
                report += mms_table(s);
              }
            }
            else
            {
              auto studies = converge_case(c, o->levels, orders, split(o->quantities), MPI_COMM_WORLD,
                                           o->stage == "surgery" ? ConvergeStage::surgery
                                                                 : ConvergeStage::preop,
                                           o->refine == "red" ? ConvergeRefinement::red
                                                              : ConvergeRefinement::gmsh);
              for (const auto& s : studies)
              {
                j["studies"].push_back(to_json(s));
                report += convergence_table(s);
              }
            }
            OutputDir dir(out, MPI_COMM_WORLD);
            write_json(dir.path() / "convergence.json", j, MPI_COMM_WORLD);
            write_text(dir.path() / "convergence.txt", report, MPI_COMM_WORLD);
            bool png = false;
            if (log::is_root())
              png = plot_convergence(dir.path() / "convergence.json", dir.path() / "convergence.png");
            dir.commit();
            if (log::is_root())
            {
              std::cout << report;
              std::cout << "results written to " << out.path().string() << "/ (convergence.json, convergence.txt"
                        << (png ? ", convergence.png" : "; no plot: python3/matplotlib failed")
                        << ")\n";
            }
            return 0;
          }};
}
} // namespace breastsim::cli
