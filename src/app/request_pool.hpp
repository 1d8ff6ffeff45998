// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The threads that answer requests: a fixed number of threads and a bounded
// queue of accepted connections. When the queue is full the listening thread
// answers the next connection itself, so it accepts no more until one is
// done and further clients wait in the kernel's backlog: memory and threads
// stay bounded under any burst.
#include <condition_variable>
#include <deque>
#include <functional>
#include <httplib.h>
#include <mutex>
#include <thread>
#include <vector>

namespace breastsim::app
{
class RequestPool : public httplib::TaskQueue
{
public:
  RequestPool(std::size_t threads, std::size_t max_queued);
  void enqueue(std::function<void()> fn) override;
  void shutdown() override;

private:
  void work();
  std::size_t _max_queued;
  std::mutex _mutex;
  std::condition_variable _wake;
  std::deque<std::function<void()>> _queue;
  std::vector<std::thread> _threads;
  bool _stop = false;
};
} // namespace breastsim::app
