// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A job's solver process: this program started again (posix_spawn, no shell)
// with stdout and stderr into a file, the default signal mask and the
// environment without the MPI launcher's variables (the child is a
// singleton MPI process of its own). SIGTERM stops it; its own interrupt
// handler removes its staging folder and terminates its picture scripts.
#include <filesystem>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace breastsim::app
{
/// Start `argv` (argv[0] a path); output into `output_file`. Throws
/// std::runtime_error if it cannot be started.
pid_t start_child(const std::vector<std::string>& argv, const std::filesystem::path& output_file);
/// The exit status of a child that has ended (exit code, or 128 + signal),
/// nothing while it runs.
std::optional<int> poll_child(pid_t pid);
/// Ask it to stop (SIGTERM); `force`: SIGKILL.
void stop_child(pid_t pid, bool force);
} // namespace breastsim::app
