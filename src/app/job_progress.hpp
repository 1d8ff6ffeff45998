// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The progress of a running job as the server's record shows it: a fraction
// (0..1) and the stage. Simulate, surgery, sweep and scan jobs report
// theirs through the structured channel (progress_channel.hpp); a
// calibration counts its evaluations (job_evaluations.hpp).
#include <string>

namespace breastsim::app
{
struct JobProgress
{
  double fraction = 0;
  std::string stage;
};

/// A calibration: `evaluations` of the misfit so far (the entries of its
/// evaluations.jsonl) over the most it may take (at most 0.95: the
/// intervals' Jacobian and the pictures follow); the stage is the log's
/// last line.
JobProgress calibration_progress(std::size_t max_evals, std::size_t evaluations, const std::string& log);
} // namespace breastsim::app
