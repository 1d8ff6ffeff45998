// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Files of a diagnosis (written into a staging result folder):
//   diagnosis.json, diagnosis.txt    the report (JSON, plain words)
//   residuals.json                   points and normal distances before/after [mm]
//   residuals_<posture>.xdmf         the same as a point cloud for ParaView
//   case.diagnosed.toml              the refitted case (discovered terms on)
//   residuals_<posture>.png          residual maps before/after (diagnose_plots.py)
//   surface_<posture>.json           the final model's skin with |residual| fields,
//   view_<posture>.png, overview.png and index.html (the 3D page; colour by
//                                    displacement or |residual| before/after)
#include "diagnosis.hpp"
#include "output_target.hpp"
#include <filesystem>
#include <mpi.h>
#include <string>

namespace breastsim::diagnosis
{
/// Collective (rank 0 writes; the pictures, only with `pictures`, run under
/// python3 on rank 0; `breastsim view` draws them later).
void write_diagnosis(const std::filesystem::path& dir, const Diagnosis& d, const Recording& rec,
                     MPI_Comm comm, bool pictures);

/// Collective. `breastsim diagnose`: diagnose `rec` against `current` and
/// write every file into `out` (staged, replaced only when complete); the
/// printable report on rank 0 ("" on the other ranks).
std::string run_diagnosis(const Recording& rec, const Config& current, const DiagnoseOptions& o,
                          const OutputTarget& out, MPI_Comm comm);
} // namespace breastsim::diagnosis
