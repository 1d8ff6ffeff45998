// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The record of one job (job.json in its folder): what was asked, its state
// and progress, the error of a failed run, the result summary of a finished
// one and the files it wrote that the API may serve (public name -> path
// relative to the job folder).
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::app
{
enum class JobState
{
  queued,
  running,
  done,
  failed,
  cancelled
};
std::string state_name(JobState s);
bool is_finished(JobState s);

struct JobRecord
{
  std::string id;
  std::string kind;        ///< simulate | surgery | calibrate
  nlohmann::json overrides = nlohmann::json::object(); ///< case keys {key: value}
  nlohmann::json options = nlohmann::json::object();   ///< calibrate: fit, max_evals
  JobState state = JobState::queued;
  double progress = 0;     ///< 0..1, by stage
  std::string stage;       ///< the last stage the solver reported
  std::string created, started, finished; ///< UTC, ISO 8601
  std::string error_kind;  ///< input | solve | error | cancelled | interrupted
  std::string error;       ///< the library's message
  nlohmann::json summary;  ///< result summary (null until done)
  std::map<std::string, std::string> files; ///< public name -> path in the job folder
};

nlohmann::json to_json(const JobRecord& r);
/// A record read back from job.json; throws std::runtime_error if malformed.
JobRecord record_from_json(const nlohmann::json& j);
/// Now, UTC, ISO 8601 (seconds).
std::string utc_now();
} // namespace breastsim::app
