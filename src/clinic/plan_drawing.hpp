// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// What the consultation's 3D view draws on a planned breast (docs/CLINIC.md,
// "Pictures"), in that breast's frame [m]: the tapes SN-N and N-IMF as
// measured on the standing skin before and after surgery, and the Wise
// pattern's marking on the standing breast before surgery.
#include "plan_search.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>

namespace breastsim::clinic
{
/// Collective. The drawing of breast `m`'s plan `best`, whose surgery was
/// written to `surgery_dir` (preop/ and postop/surface_standing.json):
/// {"before": {"sn_n": [[x, y, z], ...], "sn_n_mm", "n_imf": [...], "n_imf_mm"},
///  "after": {...}, "marking": [[[x, y, z], ...], ...], "new_nipple": [x, y, z],
///  and for a scanned side "scan": {"skin": {vertices, triangles, mirror_x},
///  "before": the tapes on the scan, "marking": the marking carried onto it}}
/// on rank 0 (null elsewhere, and where the plan was not operated).
nlohmann::json plan_drawing(const SideModel& m, const PlanOutcome& best, const std::filesystem::path& surgery_dir,
                            MPI_Comm comm);
} // namespace breastsim::clinic
