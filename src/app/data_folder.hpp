// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The server's data folder (--data): job records and results live in
// <data>/jobs/<id>/. breastsim writes only into a folder that it created (it
// carries the marker .breastsim-app) or into a new or empty one; any other
// folder, the file-system root, $HOME, the working directory and their
// ancestors are refused before the server starts.
#include <filesystem>
#include <string>

namespace breastsim::app
{
inline constexpr const char* data_marker = ".breastsim-app";

/// Normalise `given`, check it may be used, create it and its jobs/ folder
/// and write the marker. Throws InputError naming the path and the reason.
std::filesystem::path claim_data_folder(const std::string& given);
} // namespace breastsim::app
