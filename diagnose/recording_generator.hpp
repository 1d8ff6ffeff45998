// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Synthetic 3D surface recordings for proving the diagnosis: the
// case's model with one hidden candidate physics switched on (or none), on
// a finer mesh than the diagnosis uses, sampled at random points of the
// deformed skin (uniform in area) with isotropic Gaussian noise, plus the
// nipple landmark. The hidden truth is stored under "truth" (the diagnosis
// never reads it; tests and benchmarks compare against it).
#include "config.hpp"
#include "recording.hpp"
#include <mpi.h>
#include <string>

namespace breastsim::diagnosis
{
using calibration::Recording;

struct RecordingOptions
{
  std::string hidden;          ///< candidate name, "" = none (control)
  double value = 0;            ///< its parameter q (candidates.hpp); 0: the candidate's typical value
  int points = 400;            ///< points per posture
  double noise = 5e-4;         ///< noise sigma per coordinate [m]
  unsigned seed = 1;
  double mesh_size = 0;        ///< mesh of the truth [m]; 0: the case's mesh_size / 1.5
};

/// Collective. The recording of every posture requested by `c`. Throws
/// InputError on bad options (naming the option and its range).
Recording synthetic_recording(const Config& c, const RecordingOptions& o, MPI_Comm comm);
} // namespace breastsim::diagnosis
