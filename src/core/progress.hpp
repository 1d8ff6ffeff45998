// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Progress of a long job through a callback: the stage that begins and the
// fraction of the whole job done before it (0..1). A part of a job (a
// sweep's case, a surgery's postures) reports through a Progress mapped
// onto its share of the whole, so the callback always sees the fraction of
// the outermost job. Reports on every rank; the callback decides what to do.
#include <functional>
#include <string>

namespace breastsim
{
class Progress
{
public:
  using Callback = std::function<void(const std::string& stage, double fraction)>;

  Progress() = default; ///< reports nowhere
  explicit Progress(Callback callback) : _callback(std::move(callback)) {}

  /// `stage` begins after the share `done` (0..1) of this part:
  /// fraction = from + done (to - from), the stage named with the part's prefix.
  void report(const std::string& stage, double done) const;
  /// The share [from, to] (0..1) of this part, its stages prefixed by `prefix`.
  Progress part(double from, double to, const std::string& prefix = "") const;

private:
  Callback _callback;
  double _from = 0, _to = 1;
  std::string _prefix;
};
} // namespace breastsim
