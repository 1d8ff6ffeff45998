// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A dense row-major table of doubles (e.g. values at points x components),
// for the small buffers that dolfinx's expression evaluation fills.
#include <cstddef>
#include <vector>

namespace breastsim
{
struct DenseTable
{
  std::vector<double> data;
  std::size_t cols;
  double& operator()(std::size_t i, std::size_t j) { return data[i * cols + j]; }
};
} // namespace breastsim
