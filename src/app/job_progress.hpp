#pragma once
// The progress of a running job, read from the stages its solver reports in
// the job's log (log.txt, one line per info message of the library):
// meshing, each posture, sutures, post-operative postures, pictures; for a
// calibration each evaluation of the misfit ("eval N"). The fraction counts
// finished stages; the stage is the last line.
#include <string>

namespace breastsim::app
{
struct JobProgress
{
  double fraction = 0;
  std::string stage;
};

/// `kind`: simulate | surgery | calibrate | sweep; `steps`: the postures per
/// stage of the case, the calibration's largest number of evaluations, or
/// the sweep's number of combinations (one stage each).
JobProgress progress_from_log(const std::string& kind, std::size_t steps, const std::string& log);
} // namespace breastsim::app
