// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The skin of a model as a triangle surface for pictures and the 3D page:
// reference (neutral) and deformed vertex positions, gathered to rank 0. A
// half model (with a symmetry face, x >= 0) is flagged to be mirrored
// x -> -x by its readers; a full breast (no symmetry face, e.g. a scan) is
// the whole skin and is drawn as it is. A P2 mesh's curved skin triangles are
// sampled as 4 x 4 flat sub-triangles each.
#include "model.hpp"
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

namespace breastsim
{
struct SkinSurface
{
  std::vector<std::array<double, 3>> reference; ///< neutral positions [m]
  std::vector<std::array<double, 3>> deformed;  ///< reference + displacement [m]
  std::vector<std::array<std::int32_t, 3>> triangles; ///< counter-clockwise seen from outside
  bool half_model = true; ///< the half x >= 0 of a model with a symmetry face (mirror it)
};

/// Collective. Whether `model` is a half model: its mesh has facets tagged
/// "symmetry" on some rank.
bool is_half_model(const Model& model);

/// Collective. The skin surface of the current state of `model`; complete on
/// rank 0, empty on the other ranks.
SkinSurface gather_skin_surface(const Model& model);
/// Collective. As above with the displacement `u` (local and ghost dofs, the
/// layout of displacement()->x()) in place of the model's: the same
/// vertices and triangles, deformed = reference + u (sampled like the
/// displacement, so a P2 surface's deformed - reference is linear in u).
SkinSurface gather_skin_surface(const Model& model, std::span<const double> u);

/// The surface document (`surface_<posture>.json`): posture, theta_deg,
/// units, mirror_x (true: a half model, draw it with its mirror image x -> -x;
/// false: the full breast as it is), vertices_ref, vertices, triangles (flat
/// lists) and fields.displacement_mm (per vertex).
nlohmann::json surface_json(const SkinSurface& s, const std::string& posture, double theta_deg);

/// Collective. Gather the skin of `model` and write its surface document to
/// `file` (rank 0).
void write_surface(const Model& model, const std::string& posture, double theta_deg,
                   const std::filesystem::path& file);
} // namespace breastsim
