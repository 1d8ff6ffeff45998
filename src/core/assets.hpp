// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Where the program's assets are (the picture scripts and the 3D page's
// files, the planning app's page, three.js), found relative to the running
// program so that an installed breastsim and a build tree work alike:
//   <program's folder>/../share/breastsim/<name>   (cmake --install)
//   <program's folder>/share/breastsim/<name>      (the build tree, links into the sources)
// An environment variable, when set, names the folder instead.
#include <filesystem>
#include <string>

namespace breastsim
{
/// The asset folder `name` ("viewer", "app"), or $`variable` if set. Throws
/// std::runtime_error naming both places looked in if neither exists.
std::filesystem::path asset_dir(const std::string& name, const char* variable);
} // namespace breastsim
