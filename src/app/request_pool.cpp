// SPDX-License-Identifier: LGPL-3.0-or-later
#include "request_pool.hpp"

namespace breastsim::app
{
RequestPool::RequestPool(std::size_t threads, std::size_t max_queued) : _max_queued(max_queued)
{
  for (std::size_t i = 0; i < threads; ++i)
    _threads.emplace_back([this] { work(); });
}

void RequestPool::enqueue(std::function<void()> fn)
{
  {
    std::unique_lock<std::mutex> lock(_mutex);
    if (_queue.size() < _max_queued)
    {
      _queue.push_back(std::move(fn));
      lock.unlock();
      _wake.notify_one();
      return;
    }
  }
  fn(); // full: the listening thread answers this one itself (backpressure)
}

void RequestPool::shutdown()
{
  {
    std::lock_guard<std::mutex> lock(_mutex);
    _stop = true;
  }
  _wake.notify_all();
  for (auto& t : _threads)
    t.join();
}

void RequestPool::work()
{
  for (;;)
  {
    std::function<void()> fn;
    {
      std::unique_lock<std::mutex> lock(_mutex);
      _wake.wait(lock, [this] { return _stop || !_queue.empty(); });
      if (_queue.empty())
        return; // stopping and nothing left
      fn = std::move(_queue.front());
      _queue.pop_front();
    }
    fn();
  }
}
} // namespace breastsim::app
