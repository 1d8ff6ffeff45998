#pragma once
// The progress of a running job, read from the stages its solver reports in
// the job's log (log.txt, one line per info message of the library):
// meshing, each posture, sutures, post-operative postures, pictures; for a
// sweep each combination started. The fraction counts finished stages; the
// stage is the last line. A calibration counts its evaluations from the
// structured channel (job_evaluations.hpp) instead.
#include <string>

namespace breastsim::app
{
struct JobProgress
{
  double fraction = 0;
  std::string stage;
};

/// `kind`: simulate | surgery | sweep; `steps`: the postures per stage of
/// the case, or the sweep's number of combinations (one stage each).
JobProgress progress_from_log(const std::string& kind, std::size_t steps, const std::string& log);

/// A calibration: `evaluations` of the misfit so far (the entries of its
/// evaluations.jsonl) over the most it may take (at most 0.95: the
/// intervals' Jacobian and the pictures follow); the stage is the log's
/// last line.
JobProgress calibration_progress(std::size_t max_evals, std::size_t evaluations, const std::string& log);
} // namespace breastsim::app
