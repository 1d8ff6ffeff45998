// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Synthetic measurements from the forward model (for tests, examples and
// checking what a set of measurements can identify): solve the case in each
// posture, measure projection, z_min, nipple and base perimeter, and add
// independent Gaussian noise N(0, noise^2) to every value.
#include "config.hpp"
#include "posture.hpp"
#include <mpi.h>
#include <nlohmann/json.hpp>

namespace breastsim::calibration
{
struct SyntheticOptions
{
  double noise = 5e-4;  ///< standard deviation of the added noise [m]
  double sigma = 5e-4;  ///< sigma written into the file [m] (> 0)
  unsigned seed = 1;
};

/// What `breastsim measure` is asked (0: the default).
struct MeasureRequest
{
  double mesh_size = 0; ///< mesh of the truth [m]; 0: half the case's geometry.mesh_size
  double noise = 5e-4;  ///< standard deviation of the added noise [m]
  double sigma = 0;     ///< sigma written into the file [m]; 0: the noise, or 0.5 mm without noise
  unsigned seed = 1;
};
/// The case on the truth's mesh (validated; InputError).
Config measure_truth(Config c, const MeasureRequest& r);
SyntheticOptions synthetic_options(const MeasureRequest& r);

/// A measurement document (measurements.hpp format) of `truth` in its
/// requested postures. Solve on the case's own mesh: to avoid the inverse
/// crime, give `truth` a finer geometry.mesh_size than the fit will use.
nlohmann::json synthetic_measurements(const Config& truth, const SyntheticOptions& o, MPI_Comm comm);
} // namespace breastsim::calibration
