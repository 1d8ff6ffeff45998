// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_progress.hpp"
#include <algorithm>
#include <sstream>

namespace breastsim::app
{
namespace
{
/// The line without its "[hh:mm:ss] " prefix.
std::string message_of(const std::string& line)
{
  const auto p = line.find("] ");
  return p == std::string::npos ? line : line.substr(p + 2);
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
} // namespace breastsim::app
