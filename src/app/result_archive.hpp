// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A finished job's result folder as one download: a POSIX tar archive
// (ustar) of the files its marker lists, built in memory, at most
// `max_bytes` of content.
#include <cstddef>
#include <filesystem>
#include <string>

namespace breastsim::app
{
/// The archive of `result_dir` (a result folder breastsim wrote), its
/// entries named `prefix`/<path>. Throws std::runtime_error when a listed
/// file is missing, lies outside the folder or the content exceeds `max_bytes`.
std::string result_archive(const std::filesystem::path& result_dir, const std::string& prefix,
                           std::size_t max_bytes);
} // namespace breastsim::app
