// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The one timer of breastsim: dolfinx's common::Timer, so that every timed
// task is also summed in dolfinx's timing table (count, total, mean; printed
// by dolfinx::list_timings, e.g. with -v).
#include <dolfinx/common/Timer.h>
#include <string>

namespace breastsim
{
class Stopwatch
{
public:
  /// Time `task` from now; listed as "breastsim: <task>" in dolfinx's table
  /// when the stopwatch is destroyed.
  explicit Stopwatch(const std::string& task) : _timer("breastsim: " + task) {}
  /// Wall-clock seconds since construction (the stopwatch keeps running).
  double seconds() const { return _timer.elapsed()[0]; }

private:
  dolfinx::common::Timer _timer;
};
} // namespace breastsim
