// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The job process: `breastsim serve --run-job <job folder>` started by the
// server for each job. It reads request.json, logs the library's stages into
// log.txt, runs simulate(), surgery() or the calibration into <job
// folder>/result (claimed and staged like any result folder) and writes
// outcome.json: {"ok": true} or {"ok": false, "error_kind":
// input|solve|error, "error": message}. A calibration's measurements go into
// the job's measurements.json, its checkpoint into checkpoint.json.
#include <filesystem>

namespace breastsim::app
{
/// Exit code as the CLI's: 0, 2 input, 3 solve, 1 other. Stops (SIGTERM
/// to itself) when the server process ends.
int run_job(const std::filesystem::path& job_folder);
} // namespace breastsim::app
