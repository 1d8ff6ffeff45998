// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The page's files, served read-only from a fixed table (URL -> file): the
// app (src/app/web) and three.js with its orbit controls
// (src/viewer/web/node_modules/three). No other file is reachable. The
// folders are the source tree's, or $BREASTSIM_APP_WEB_DIR and
// $BREASTSIM_THREE_DIR.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace breastsim::app
{
struct StaticFile
{
  std::filesystem::path file;
  std::string mime;
};

/// The file behind `url_path`, or nothing if the table has no such URL.
std::optional<StaticFile> static_file(const std::string& url_path);
/// The URLs of the table.
std::vector<std::string> static_urls();
} // namespace breastsim::app
