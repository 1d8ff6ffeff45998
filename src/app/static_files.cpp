// SPDX-License-Identifier: LGPL-3.0-or-later
#include "static_files.hpp"
#include "assets.hpp"
#include <array>
#include <cstdlib>
#include <vector>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
struct Entry
{
  const char* url;
  bool three; ///< in three.js's package, else in the app's folder
  const char* file;
  const char* mime;
};

constexpr std::array<Entry, 12> table = {{
    {"/", false, "app.html", "text/html; charset=utf-8"},
    {"/index.html", false, "app.html", "text/html; charset=utf-8"},
    {"/app.js", false, "app.js", "text/javascript; charset=utf-8"},
    {"/app.css", false, "app.css", "text/css; charset=utf-8"},
    {"/view3d.js", false, "view3d.js", "text/javascript; charset=utf-8"},
    {"/report.js", false, "report.js", "text/javascript; charset=utf-8"},
    {"/sweep.js", false, "sweep.js", "text/javascript; charset=utf-8"},
    {"/misfit_plot.js", false, "misfit_plot.js", "text/javascript; charset=utf-8"},
    {"/patient_files.js", false, "patient_files.js", "text/javascript; charset=utf-8"},
    {"/consult.js", false, "consult.js", "text/javascript; charset=utf-8"},
    {"/three/three.module.js", true, "build/three.module.js", "text/javascript; charset=utf-8"},
    {"/three/OrbitControls.js", true, "examples/jsm/controls/OrbitControls.js",
     "text/javascript; charset=utf-8"},
}};
} // namespace

std::optional<StaticFile> static_file(const std::string& url_path)
{
  for (const auto& e : table)
    if (url_path == e.url)
    {
      const fs::path dir = e.three ? asset_dir("viewer", "BREASTSIM_VIEWER_DIR") / "web/node_modules/three"
                                   : asset_dir("app", "BREASTSIM_APP_WEB_DIR");
      return StaticFile{dir / e.file, e.mime};
    }
  return std::nullopt;
}

std::vector<std::string> static_urls()
{
  std::vector<std::string> urls;
  for (const auto& e : table)
    urls.emplace_back(e.url);
  return urls;
}
} // namespace breastsim::app
