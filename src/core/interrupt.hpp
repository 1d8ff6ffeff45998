// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// SIGINT, SIGTERM, SIGHUP and SIGPIPE: the run stops, its staging folders and
// lock files are removed, its child processes (picture scripts) are
// terminated, and the process exits with 128 + signal (130, 143, 129, 141). A dedicated thread receives the
// signals (they are blocked in every other thread), so the clean-up runs
// outside a signal handler.
#include <filesystem>
#include <string>
#include <vector>

namespace breastsim::interrupt
{
/// Block SIGINT/SIGTERM/SIGHUP in this (the main) thread and start the thread
/// that handles them; SIGXFSZ is ignored (an over-large write fails with
/// EFBIG and is reported). Call first in main(), before any thread is created.
void install();

/// A write to a closed pipe (`breastsim ... | head`) stops the run like
/// SIGTERM, exit code 141. Call after PETSc is initialised (PETSc's own
/// signal handlers removed), so that this handler is the one in place.
void stop_on_broken_pipe();
/// A server: a client that hung up must not stop it (writes fail with EPIPE).
void ignore_broken_pipe();

/// Remove `p` (a folder: recursively) when the run is interrupted.
void register_path(const std::filesystem::path& p);
void unregister_path(const std::filesystem::path& p);

/// Run `argv` (no shell) as a child process with the default signal mask and
/// wait for it; an interrupt terminates it. Returns its exit code, or -1 if it
/// could not be started or did not exit normally.
int run_child(const std::vector<std::string>& argv);
} // namespace breastsim::interrupt
