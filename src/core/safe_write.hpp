// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Writing files without following symbolic links: a link planted where
// breastsim writes makes the write fail (ELOOP) instead of writing through it.
#include <filesystem>
#include <string>

namespace breastsim
{
enum class Existing
{
  replace, ///< truncate a regular file of that name
  refuse   ///< fail (EEXIST) if anything of that name exists
};

/// Write `text` to `file`, never through a symbolic link (O_NOFOLLOW). Throws
/// std::system_error carrying errno (ELOOP for a link, ENOSPC for a full disk).
void write_file_nofollow(const std::filesystem::path& file, const std::string& text,
                         Existing existing = Existing::replace);
} // namespace breastsim
