// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The `scan-model` job: a skin scan (and optionally a chest-wall surface)
// recorded in a posture becomes a tagged mesh and a case in the breast frame
// (src/scan/scan_model.hpp). Written into the output folder:
//   scan.msh      tetrahedra "tissue", surfaces "base", "skin" (and
//                 "symmetry" for a half model), in metres, breast frame;
//   case.toml     geometry.mesh_file = "scan.msh", the nipple node
//                 (geometry.H, geometry.nipple_z), geometry.R = the mean
//                 footprint radius, the scan's posture; `simulate` and
//                 `neutral-state` read it;
//   frame.json    the map between the scanner frame and the breast frame
//                 (x_scanner = origin + X e_x + Y e_y + Z e_z, metres);
//   summary.json  counts, fit RMS and noise, nipple, footprint, the chest
//                 wall against the chest plane, volume.
// Nothing is written when the scan is refused (InputError, exit code 2).
#include "config.hpp"
#include "output_target.hpp"
#include "posture.hpp"
#include "scan_model.hpp"
#include <filesystem>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>

namespace breastsim
{
struct ScanModelRequest
{
  std::filesystem::path skin;
  std::optional<std::filesystem::path> chest;
  scan::ScanModelOptions options;
  Posture posture;
  std::string name = "scan"; ///< case.name of the written case
};

struct ScanModelResult
{
  scan::ScanModel model; ///< on rank 0 (the mesh is not kept)
  std::size_t cells = 0;
};

ScanModelResult scan_model(const ScanModelRequest& r, const OutputTarget& out, MPI_Comm comm);
std::string scan_model_table(const ScanModelResult& r);

/// The chest wall against the chest plane (summary.json "chest"; radii of
/// a flat direction are null).
nlohmann::json chest_json(const scan::ChestCurvature& c);

/// The case of a scan's mesh (geometry.mesh_file = `mesh_file`) in `posture`.
Config scan_case(const scan::ScanModel& m, const std::string& mesh_file, const Posture& posture,
                 const std::string& name);
} // namespace breastsim
