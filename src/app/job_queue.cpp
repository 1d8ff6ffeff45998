// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_queue.hpp"
#include "case_request.hpp"
#include "child_process.hpp"
#include "job_evaluations.hpp"
#include "job_progress.hpp"
#include "log.hpp"
#include "output_target.hpp"
#include "progress_channel.hpp"
#include "result_summary.hpp"
#include "upload_summaries.hpp"
#include <algorithm>
#include <chrono>
#include <fstream>
#include <sstream>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
std::string read_text(const fs::path& file)
{
  std::ifstream f(file);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

/// The job's outcome.json, or an error naming how the process ended.
nlohmann::json outcome_of(const fs::path& folder, int exit_code)
{
  const auto j = nlohmann::json::parse(read_text(folder / "outcome.json"), nullptr, false);
  if (j.is_object() && j.contains("ok"))
    return j;
  return {{"ok", false},
          {"error_kind", "error"},
          {"error", exit_code > 128 ? "the job process ended with signal " + std::to_string(exit_code - 128)
                                    : "the job process ended with exit code " + std::to_string(exit_code) +
                                          " (its output: output.txt in the job folder)"}};
}
/// A scan uploaded for the consultation: kept for a patient's model, not modelled (no result/).
bool kept_scan(const JobRecord& r)
{
  return r.kind == "scan" && r.options.at("scan").value("use", "model") == "consultation";
}

/// The summary of a finished job: a recording's calibration (diagnosis.json)
/// and a scan job by their own readers, the rest from result/.
nlohmann::json summary_of(const JobRecord& r, const fs::path& folder)
{
  if (r.kind == "surgery" && r.options.contains("scan")) // the scan's neutral case with the plan, as solved
    return summarize_result(r.kind, Config::from_file(folder / "result" / "case.resolved.toml"), folder / "result");
  const Config c = case_from_overrides(r.overrides);
  if (kept_scan(r))
    return {{"kind", "scan"}, {"use", "consultation"}, {"bytes", r.options.at("scan").at("bytes")}};
  if (r.kind == "scan")
    return summarize_scan(c, folder);
  if (r.kind == "calibrate" && fs::exists(folder / "result" / "diagnosis.json"))
    return summarize_recording_fit(c, folder / "result");
  return summarize_result(r.kind, c, folder / "result");
}
} // namespace

JobQueue::JobQueue(JobStore& store, std::string program, int workers, std::size_t max_queued)
    : _store(store), _program(std::move(program)), _max_queued(max_queued)
{
  for (const auto& id : _store.queued())
    _queue.push_back(id);
  for (int i = 0; i < workers; ++i)
    _workers.emplace_back([this] { work(); });
}

JobQueue::~JobQueue()
{
  {
    std::lock_guard<std::mutex> lock(_mutex);
    _stop = true;
    for (const auto& [id, pid] : _running)
      if (pid > 0)
        stop_child(pid, false);
  }
  _wake.notify_all();
  for (auto& t : _workers)
    t.join();
}

bool JobQueue::submit(const std::string& id)
{
  {
    std::lock_guard<std::mutex> lock(_mutex);
    if (_queue.size() >= _max_queued)
      return false;
    _queue.push_back(id);
  }
  _wake.notify_one();
  return true;
}

bool JobQueue::cancel(const std::string& id)
{
  std::unique_lock<std::mutex> lock(_mutex);
  if (auto it = std::find(_queue.begin(), _queue.end(), id); it != _queue.end())
  {
    _queue.erase(it);
    lock.unlock();
    _store.update(id, [](JobRecord& r) {
      r.state = JobState::cancelled;
      r.error_kind = "cancelled";
      r.error = "cancelled before it started";
      r.finished = utc_now();
    });
    return true;
  }
  if (auto it = _running.find(id); it != _running.end())
  {
    _cancelled.insert(id);
    if (it->second > 0)
      stop_child(it->second, false);
    return true;
  }
  return false;
}

void JobQueue::work()
{
  for (;;)
  {
    std::string id;
    {
      std::unique_lock<std::mutex> lock(_mutex);
      _wake.wait(lock, [this] { return _stop || !_queue.empty(); });
      if (_stop)
        return;
      id = _queue.front();
      _queue.pop_front();
      _running[id] = 0; // starting: a cancel now is seen once the process exists
    }
    try
    {
      run(id);
    }
    catch (const std::exception& e)
    {
      {
        std::lock_guard<std::mutex> lock(_mutex);
        _running.erase(id);
        _cancelled.erase(id);
      }
      log::warn("serve: job {}: {}", id, e.what());
      _store.update(id, [&](JobRecord& r) {
        r.state = JobState::failed;
        r.error_kind = "error";
        r.error = e.what();
        r.finished = utc_now();
      });
    }
  }
}

void JobQueue::run(const std::string& id)
{
  const fs::path folder = _store.folder(id);
  _store.update(id, [](JobRecord& r) {
    r.state = JobState::running;
    r.started = utc_now();
    r.stage = "starting";
  });
  const auto record = *_store.get(id);
  log::info("serve: job {} ({}) started", id, record.kind);
  int exit_code = 0;
  pid_t pid = 0;
  {
    std::lock_guard<std::mutex> lock(_mutex); // a cancel sees the pid as soon as it exists
    pid = start_child({_program, "serve", "--run-job", folder.string()}, folder / "output.txt");
    _running[id] = pid;
  }
  bool asked_to_stop = false;
  auto stop_asked_at = std::chrono::steady_clock::now();
  for (;;)
  {
    if (const auto code = poll_child(pid))
    {
      exit_code = *code;
      break;
    }
    refresh_progress(id, record);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::lock_guard<std::mutex> lock(_mutex);
    if (!asked_to_stop && (_stop || _cancelled.count(id)))
    {
      asked_to_stop = true;
      stop_asked_at = std::chrono::steady_clock::now();
      stop_child(pid, false);
    }
    else if (asked_to_stop && std::chrono::steady_clock::now() - stop_asked_at > std::chrono::seconds(10))
      stop_child(pid, true); // it did not stop within 10 s
  }
  bool cancelled;
  {
    std::lock_guard<std::mutex> lock(_mutex);
    _running.erase(id);
    cancelled = _cancelled.erase(id) > 0 || _stop;
  }
  finish(id, exit_code, cancelled);
}

void JobQueue::refresh_progress(const std::string& id, const JobRecord& r)
{
  try
  {
    const fs::path folder = _store.folder(id);
    const auto p = r.kind == "calibrate"
                       ? calibration_progress(r.options.value("max_evals", 1), read_evaluations(folder).size(),
                                              read_text(folder / "log.txt"))
                       : last_progress(read_text(folder / progress_file));
    _store.update(id, [&](JobRecord& rec) {
      rec.progress = p.fraction;
      rec.stage = p.stage.empty() ? rec.stage : p.stage;
    });
  }
  catch (const std::exception& e)
  {
    log::warn("serve: job {}: progress: {}", id, e.what());
  }
}

void JobQueue::finish(const std::string& id, int exit_code, bool cancelled)
{
  const fs::path folder = _store.folder(id);
  remove_stale_staging(folder / "result"); // of a job process killed before its own clean-up
  const auto record = *_store.get(id);
  JobRecord result = record;
  result.finished = utc_now();
  if (cancelled && exit_code != 0)
  {
    result.state = JobState::cancelled;
    result.error_kind = "cancelled";
    result.error = "cancelled while running (" + result.stage + ")";
    std::error_code ec; // the job process's progress is no result: a cancelled job keeps its records only
    fs::remove(folder / progress_file, ec);
  }
  else if (const auto outcome = outcome_of(folder, exit_code); exit_code == 0 && outcome.value("ok", false))
  {
    result.state = JobState::done;
    result.progress = 1;
    result.stage = "finished";
    result.summary = summary_of(record, folder);
    result.files = kept_scan(record) ? std::map<std::string, std::string>{{"log.txt", "log.txt"}} : result_files(folder);
    if (record.kind == "scan" && !kept_scan(record))
      result.files.merge(scan_files());
    if (fs::exists(folder / progress_file))
      result.files[progress_file] = progress_file;
  }
  else
  {
    result.state = JobState::failed;
    result.error_kind = outcome.value("error_kind", "error");
    result.error = outcome.value("error", "unknown error");
  }
  _store.update(id, [&](JobRecord& r) { r = result; });
  log::info("serve: job {} ({}) {}{}", id, result.kind, state_name(result.state),
            result.error.empty() ? "" : ": " + result.error);
}

bool submit_or_fail(JobStore& store, JobQueue& queue, const std::string& id)
{
  if (queue.submit(id))
    return true;
  store.update(id, [](JobRecord& rec) {
    rec.state = JobState::failed;
    rec.error_kind = "error";
    rec.error = "the job queue is full";
    rec.finished = utc_now();
  });
  return false;
}
} // namespace breastsim::app
