// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The queue of long work: `workers` threads each run one job at a time as a
// child process of this program (job_runner), so a crashing or failing solve
// never takes the server down and a job can be cancelled at any moment
// (SIGTERM: the job's own clean-up removes its staging folder). While a job
// runs, its record's progress is refreshed from its log; when it ends the
// record gets its state, its error (outcome.json) or its result summary.
#include "job_store.hpp"
#include <condition_variable>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace breastsim::app
{
class JobQueue
{
public:
  /// `program`: this program's path, run as `program serve --run-job <folder>`.
  JobQueue(JobStore& store, std::string program, int workers, std::size_t max_queued);
  ~JobQueue(); ///< stops the running jobs and the workers
  JobQueue(const JobQueue&) = delete;
  JobQueue& operator=(const JobQueue&) = delete;

  /// Queue a job; false if the queue is full.
  bool submit(const std::string& id);
  /// Cancel a queued or running job; false if it has already finished.
  bool cancel(const std::string& id);

private:
  void work();
  void run(const std::string& id);
  void finish(const std::string& id, int exit_code, bool cancelled);
  void refresh_progress(const std::string& id, const JobRecord& r);

  JobStore& _store;
  std::string _program;
  std::size_t _max_queued;
  std::mutex _mutex;
  std::condition_variable _wake;
  std::deque<std::string> _queue;
  std::map<std::string, pid_t> _running;
  std::set<std::string> _cancelled;
  bool _stop = false;
  std::vector<std::thread> _workers;
};
/// Queue job `id`; when the queue is full its record is marked failed
/// ("the job queue is full") and false is returned (the API answers 429).
bool submit_or_fail(JobStore& store, JobQueue& queue, const std::string& id);
} // namespace breastsim::app
