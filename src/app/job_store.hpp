// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The job records under <data>/jobs/<id>/: job.json (the record, written
// only by the server, atomically through a temporary sibling) and
// request.json (what the job process reads). Records of earlier server runs
// are loaded at start; a job that was running when its server stopped is
// marked failed ("interrupted"), queued jobs are queued again.
#include "job_record.hpp"
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

namespace breastsim::app
{
class JobStore
{
public:
  /// Load every record below `data`/jobs (a claimed data folder).
  explicit JobStore(const std::filesystem::path& data);
  /// A new queued job for a checked request {kind, overrides, ...}: its
  /// folder, request.json (the whole request) and job.json.
  JobRecord create(const nlohmann::json& request);
  std::optional<JobRecord> get(const std::string& id) const;
  /// Every record, oldest first.
  std::vector<JobRecord> list() const;
  /// Change a record under the store's lock and save it.
  void update(const std::string& id, const std::function<void(JobRecord&)>& change);
  /// Ids of the queued jobs (oldest first), to queue again after a restart.
  std::vector<std::string> queued() const;
  std::filesystem::path folder(const std::string& id) const;

private:
  void save(const JobRecord& r) const;
  std::filesystem::path _jobs;
  mutable std::mutex _mutex;
  std::vector<JobRecord> _records;
};
} // namespace breastsim::app
