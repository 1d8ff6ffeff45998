// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_store.hpp"
#include "job_id.hpp"
#include "log.hpp"
#include "output_target.hpp"
#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
void write_file_atomically(const fs::path& file, const std::string& text)
{
  const fs::path tmp = file.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::trunc);
    f << text;
    if (!f.flush())
      throw std::runtime_error("cannot write " + tmp.string() + " (disk full?)");
  }
  fs::rename(tmp, file);
}

/// A record of an earlier server run, or nothing (with a warning) if unreadable.
std::optional<JobRecord> load_record(const fs::path& dir)
{
  try
  {
    std::ifstream f(dir / "job.json");
    auto r = record_from_json(nlohmann::json::parse(f));
    if (r.id != dir.filename().string())
      throw std::runtime_error("its id differs from the folder name");
    return r;
  }
  catch (const std::exception& e)
  {
    log::warn("serve: skipping job folder {}: {}", dir.string(), e.what());
    return std::nullopt;
  }
}
} // namespace

JobStore::JobStore(const fs::path& data) : _jobs(data / "jobs")
{
  for (const auto& entry : fs::directory_iterator(_jobs))
  {
    const auto name = entry.path().filename().string();
    if (!entry.is_directory() || !is_job_id(name) || !fs::exists(entry.path() / "job.json"))
      continue;
    auto r = load_record(entry.path());
    if (!r)
      continue;
    if (r->state == JobState::running)
    {
      r->state = JobState::failed;
      r->error_kind = "interrupted";
      r->error = "the server stopped while this job was running";
      r->finished = utc_now();
      remove_stale_staging(entry.path() / "result");
      save(*r);
    }
    _records.push_back(std::move(*r));
  }
  std::sort(_records.begin(), _records.end(),
            [](const JobRecord& a, const JobRecord& b) { return a.created < b.created; });
}

JobRecord JobStore::create(const nlohmann::json& request)
{
  JobRecord r;
  r.kind = request.at("kind");
  r.overrides = request.value("overrides", nlohmann::json::object());
  for (const char* option : {"fit", "max_evals", "vary", "scan"})
    if (request.contains(option))
      r.options[option] = request.at(option);
  if (r.kind == "calibrate")
    r.options["data"] = request.contains("recording") ? "recording" : "measurements";
  r.created = utc_now();
  r.files = {{"log.txt", "log.txt"}}; // readable while the job runs
  std::lock_guard<std::mutex> lock(_mutex);
  do
    r.id = new_job_id();
  while (fs::exists(_jobs / r.id));
  fs::create_directory(_jobs / r.id);
  write_file_atomically(_jobs / r.id / "request.json", request.dump(2));
  save(r);
  _records.push_back(r);
  return r;
}

std::optional<JobRecord> JobStore::get(const std::string& id) const
{
  std::lock_guard<std::mutex> lock(_mutex);
  for (const auto& r : _records)
    if (r.id == id)
      return r;
  return std::nullopt;
}

std::vector<JobRecord> JobStore::list() const
{
  std::lock_guard<std::mutex> lock(_mutex);
  return _records;
}

void JobStore::update(const std::string& id, const std::function<void(JobRecord&)>& change)
{
  std::lock_guard<std::mutex> lock(_mutex);
  for (auto& r : _records)
    if (r.id == id)
    {
      change(r);
      save(r);
      return;
    }
  throw std::runtime_error("no job " + id);
}

std::vector<std::string> JobStore::queued() const
{
  std::lock_guard<std::mutex> lock(_mutex);
  std::vector<std::string> ids;
  for (const auto& r : _records)
    if (r.state == JobState::queued)
      ids.push_back(r.id);
  return ids;
}

fs::path JobStore::folder(const std::string& id) const
{
  if (!is_job_id(id))
    throw std::invalid_argument("not a job id");
  return _jobs / id;
}

void JobStore::save(const JobRecord& r) const
{
  write_file_atomically(_jobs / r.id / "job.json", to_json(r).dump(2));
}
} // namespace breastsim::app
