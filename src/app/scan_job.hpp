// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A scan job in the job process: the uploaded skin scan (stored by the
// server as <job folder>/scan.<format>) becomes the patient's model as the
// CLI makes it (docs/SCANS.md): scan-model into <job>/model, neutral-state
// in the scan's posture into <job>/neutral, then simulate of the neutral
// case in standing, supine and all fours into <job>/result (the scanned
// breast in each posture, for the page's 3D view). Each step claims and
// commits its folder like the CLI's --out.
#include "output_target.hpp"
#include "progress.hpp"
#include <filesystem>
#include <nlohmann/json.hpp>

namespace breastsim::app
{
/// The postures the scanned breast is simulated in.
inline const char* scan_postures[] = {"standing", "supine", "all_fours"};

/// The scan's neutral case in its job folder (written by neutral-state).
inline const char* scan_neutral_case = "neutral/case.reference.toml";

/// `request`: {"kind": "scan", "scan": {"file", "format", "units", "posture",
/// "mesh_size"}} as the server checked it. Throws the library's errors.
void run_scan_job(const std::filesystem::path& folder, const nlohmann::json& request, const OutputRules& rules,
                  const Progress& progress);

/// A surgery job on a scanned breast (`request`: {"kind": "surgery",
/// "scan": id, "overrides"} as the server checked it): full_breast_surgery
/// of the scan job's neutral case (`scan_folder`/neutral/case.reference.toml)
/// with the request's incision, posture and surgery keys, into `out`.
void run_scan_surgery(const std::filesystem::path& scan_folder, const nlohmann::json& request,
                      const OutputTarget& out, const Progress& progress);
} // namespace breastsim::app
