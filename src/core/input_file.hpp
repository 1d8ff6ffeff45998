// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Input files checked once, at the edge: a missing file, a symbolic-link loop,
// a folder, a named pipe or a device is refused (InputError, exit code 2) with
// a message that names the file and says what it is.
#include <filesystem>
#include <string>
#include <system_error>

namespace breastsim
{
/// What the entry at `p` is, for a message: "a folder", "a named pipe (FIFO)",
/// "a socket", "a device", "a symbolic link to nothing", "a regular file", ...
/// (does not follow a final symbolic link).
std::string entry_kind(const std::filesystem::path& p);

/// Throws InputError unless `path` names a readable regular file (symbolic
/// links followed). `what` names it in the message, e.g. "case file".
void check_input_file(const std::filesystem::path& path, const std::string& what);

/// A file-system error in plain words: "Permission denied", "No space left on
/// device" (the std::filesystem_error prefix and quoting left out).
std::string plain_error(const std::exception& e);
} // namespace breastsim
