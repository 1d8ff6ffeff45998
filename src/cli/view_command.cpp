// SPDX-License-Identifier: LGPL-3.0-or-later
// `breastsim view RESULT_DIR`: (re)render the pictures of a result folder and
// write its self-contained 3D page index.html.
#include "errors.hpp"
#include "log.hpp"
#include "output.hpp"
#include "viewer.hpp"
#include "command.hpp"
#include <fmt/format.h>
#include <iostream>
#include <memory>

namespace breastsim::cli
{
Command add_view_command(CLI::App& root)
{
  struct Options
  {
    std::string result_dir, compare, size = "800x600";
  };
  auto o = std::make_shared<Options>();
  auto* app = root.add_subcommand(
      "view", "pictures (PNG) and a 3D page (index.html, opens offline in a browser) of a result");
  app->add_option("result_dir", o->result_dir, "result folder of `breastsim simulate`")
      ->required()
      ->check(CLI::ExistingDirectory);
  app->add_option("--compare", o->compare,
                  "second result folder (e.g. pre vs post-operative): compare_<posture>.png and "
                  "a pre/post toggle in the page")
      ->check(CLI::ExistingDirectory);
  app->add_option("--size", o->size, "picture size WIDTHxHEIGHT in pixels")
      ->capture_default_str();
  return {app, [o]()
          {
            // Pictures are written only into a finished result folder of breastsim's own,
            // rendered beside it and moved in file by file (never through a link).
            const auto dir = normalise_path(o->result_dir, "result_dir");
            if (!std::filesystem::exists(std::filesystem::symlink_status(dir / result_marker)))
              throw InputError(fmt::format("refusing to write pictures into '{}': it has no {} "
                                           "marker, so breastsim did not write it",
                                           dir.string(), result_marker));
            OutputRules rules; // a finished, marked folder with nothing foreign in it;
            rules.protect = {"/", "", ""}; // `view .` inside a result folder is fine
            const auto target = OutputTarget::claim(dir.string(), rules, MPI_COMM_WORLD);
            check_picture_tools(MPI_COMM_WORLD);
            OutputDir staging(target, MPI_COMM_WORLD);
            const bool surgery = o->compare.empty() && is_surgery_result(dir);
            if (surgery) // pre-op, post-op against pre-op, and the page in postop/
              render_surgery_pictures(dir, {"", o->size, staging.path()}, MPI_COMM_WORLD);
            else
            {
              render_pictures(dir, {o->compare, o->size, staging.path()}, MPI_COMM_WORLD);
              write_view_page(dir, o->compare, MPI_COMM_WORLD, staging.path() / "index.html");
            }
            if (std::filesystem::is_regular_file(dir / "residuals.json")) // a diagnosis: its residual maps
              run_viewer_script("diagnose_plots.py", {dir.string(), staging.path().string()},
                                "residual maps of " + dir.string(), MPI_COMM_WORLD);
            staging.commit_files(); // the marker lists the pictures too
            if (log::is_root())
            {
              const auto page = std::filesystem::absolute(o->result_dir)
                                / (surgery ? "postop/index.html" : "index.html");
              std::cout << "pictures written to " << o->result_dir
                        << "/ (view_<posture>.png, overview.png"
                        << (o->compare.empty() ? "" : ", compare_<posture>.png") << ")\n"
                        << "3D page: file://" << page.lexically_normal().string() << "\n";
            }
            return 0;
          }};
}
} // namespace breastsim::cli
