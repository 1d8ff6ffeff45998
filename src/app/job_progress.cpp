#include "job_progress.hpp"
#include <algorithm>
#include <sstream>

namespace breastsim::app
{
namespace
{
bool has(const std::string& line, const char* text) { return line.find(text) != std::string::npos; }

/// The line without its "[hh:mm:ss] " prefix.
std::string message_of(const std::string& line)
{
  const auto p = line.find("] ");
  return p == std::string::npos ? line : line.substr(p + 2);
}

/// Combinations of a sweep started ("sweep: <label> (group ...)") over their number.
JobProgress sweep_progress(std::size_t combinations, const std::string& log)
{
  JobProgress p;
  std::istringstream in(log);
  std::string line;
  double started = 0;
  while (std::getline(in, line))
    if (!line.empty())
    {
      p.stage = message_of(line);
      if (p.stage.rfind("sweep: ", 0) == 0 && has(line, "(group "))
        started += 1;
    }
  p.fraction = std::min(0.99, std::max(0.0, started - 1) / static_cast<double>(std::max<std::size_t>(combinations, 1)));
  return p;
}
} // namespace

JobProgress calibration_progress(std::size_t max_evals, std::size_t evaluations, const std::string& log)
{
  JobProgress p;
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty())
      p.stage = message_of(line);
  p.fraction = std::min(0.95, static_cast<double>(evaluations) / static_cast<double>(std::max<std::size_t>(max_evals, 1)));
  return p;
}

JobProgress progress_from_log(const std::string& kind, std::size_t steps, const std::string& log)
{
  if (kind == "sweep")
    return sweep_progress(steps, log);
  const std::size_t postures = steps;
  const bool surgery = kind == "surgery";
  // Stages: meshing, each posture (twice for surgery, with the sutures
  // between), then the pictures after the last posture.
  const double total = surgery ? 2.0 * postures + 3 : postures + 2.0;
  double done = 0;
  std::size_t solving = 0; // "solving posture" lines seen
  JobProgress p;
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.empty())
      continue;
    p.stage = message_of(line);
    if (has(line, "surgery: pre-operative postures") || has(line, "model: "))
      done = std::max(done, 1.0);
    else if (has(line, "solving posture"))
    {
      // the k-th solve (k from 0) follows k finished postures, and for the
      // post-operative ones also the sutures
      const double after_sutures = surgery && solving >= postures ? 1.0 : 0.0;
      done = std::max(done, 1.0 + static_cast<double>(solving) + after_sutures);
      ++solving;
    }
    else if (has(line, "closing the sutures"))
      done = std::max(done, 1.0 + postures);
    else if (has(line, "surgery: post-operative postures"))
      done = std::max(done, 2.0 + postures);
  }
  p.fraction = std::min(0.99, done / total);
  return p;
}
} // namespace breastsim::app
