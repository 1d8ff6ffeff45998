// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Breast reduction on a full breast (geometry.mesh_file without a
// "symmetry" group: a scan's mesh or its neutral reference): the skin of the
// neutral mesh fitted (scan/skin_solid.hpp), the incision built on that
// shape in the breast's own frame (scan/full_breast_incision.hpp), the keel
// faces sewn to each other and the P2 face to the chest
// (full_breast_sutures.hpp), the final neutral state, the post-operative
// postures. Volumes are the full breast's (no mirror factor).
#include "full_breast_incision.hpp"
#include "partner_field.hpp"
#include "surgery.hpp"

namespace breastsim
{
struct FullBreastSurgeryResult
{
  SurgeryResult base;               ///< incision: A, B, C, D, P1, P2; cap_volume: the fitted solid's
  scan::FullIncisionGeometry incision;
  double skin_fit_rms = 0;          ///< RMS radial distance of the neutral skin nodes to the fit [m]
  double volume_kept_cad = 0, volume_resected_cad = 0; ///< [m^3]
  double gap_tissue = 0, gap_chest = 0;                 ///< final gaps of the two sutures [m]
  PartnerImageStats keel_images; ///< face A's nodes whose mirror images lie beyond face B's cells
  bool face_a_on_mirror = false; ///< suture_a (sewn to its mirror image) is the keel face on P1' (x < 0)
};

/// True when geometry.mesh_file is set: surgery on the user's (full) breast
/// (full_breast_surgery refuses a half model's mesh).
bool is_full_breast_case(const Config& c);

/// The whole surgery job on a full breast; writes into `out` (replaced only on success).
/// `progress`: as surgery()'s: meshing, each pre-operative posture, the
/// sutures, each post-operative posture, the pictures (2 N + 3 stages of
/// equal share), finished.
FullBreastSurgeryResult full_breast_surgery(const Config& c, const OutputTarget& out, MPI_Comm comm,
                                            const Progress& progress = {});
nlohmann::json to_json(const FullBreastSurgeryResult& r);
} // namespace breastsim
