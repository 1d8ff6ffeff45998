// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_record.hpp"
#include <array>
#include <ctime>
#include <stdexcept>

namespace breastsim::app
{
namespace
{
const std::array<std::pair<JobState, const char*>, 5> state_names = {
    {{JobState::queued, "queued"}, {JobState::running, "running"}, {JobState::done, "done"},
     {JobState::failed, "failed"}, {JobState::cancelled, "cancelled"}}};

JobState state_from_name(const std::string& n)
{
  for (const auto& [s, name] : state_names)
    if (n == name)
      return s;
  throw std::runtime_error("unknown job state '" + n + "'");
}
} // namespace

std::string state_name(JobState s)
{
  for (const auto& [st, name] : state_names)
    if (st == s)
      return name;
  return "unknown";
}

bool is_finished(JobState s) { return s == JobState::done || s == JobState::failed || s == JobState::cancelled; }

nlohmann::json to_json(const JobRecord& r)
{
  nlohmann::json files = nlohmann::json::array();
  for (const auto& [name, _] : r.files)
    files.push_back(name);
  return {{"id", r.id}, {"kind", r.kind}, {"overrides", r.overrides}, {"options", r.options},
          {"state", state_name(r.state)},
          {"progress", r.progress}, {"stage", r.stage}, {"created", r.created},
          {"started", r.started}, {"finished", r.finished}, {"error_kind", r.error_kind},
          {"error", r.error}, {"summary", r.summary}, {"files", files}, {"file_paths", r.files}};
}

JobRecord record_from_json(const nlohmann::json& j)
{
  JobRecord r;
  r.id = j.at("id").get<std::string>();
  r.kind = j.at("kind").get<std::string>();
  r.overrides = j.at("overrides");
  r.options = j.value("options", nlohmann::json::object());
  r.state = state_from_name(j.at("state").get<std::string>());
  r.progress = j.value("progress", 0.0);
  r.stage = j.value("stage", "");
  r.created = j.value("created", "");
  r.started = j.value("started", "");
  r.finished = j.value("finished", "");
  r.error_kind = j.value("error_kind", "");
  r.error = j.value("error", "");
  r.summary = j.value("summary", nlohmann::json());
  r.files = j.value("file_paths", std::map<std::string, std::string>{});
  return r;
}

std::string utc_now()
{
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}
} // namespace breastsim::app
