// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Calibration checkpoint: the best parameters so far and the number of
// evaluations, rewritten (atomically) after every evaluation so that an
// interrupted run can be resumed with --resume.
#include "fit_parameters.hpp"
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace breastsim::calibration
{
struct Checkpoint
{
  std::vector<std::string> names; ///< fitted parameters, in order
  std::vector<double> best_y;     ///< ln of the best parameters so far
  double best_chi2 = 0;
  int evaluations = 0;
};

/// Write `cp` to `file` (rank 0; via a temporary file and rename).
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& cp);
/// Read a checkpoint and check it belongs to a fit of `fit`. Throws InputError.
Checkpoint read_checkpoint(const std::filesystem::path& file, const std::vector<FitParameter>& fit);
} // namespace breastsim::calibration
