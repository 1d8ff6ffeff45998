// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Breast reduction surgery (docs/MODEL.md): pre-operative postures, incision by the
// planes P1 and P2 with remeshing, suturing (knitting conditions) without
// gravity, the final neutral state (stresses reset), and the post-operative
// postures from it.
#include "incision.hpp"
#include "simulate.hpp"
#include "surgery_options.hpp"
#include <functional>

namespace breastsim
{
struct SutureReport
{
  double max_gap = 0;       ///< largest distance of a suture node to its plane [m]
  double k_final = 0;       ///< penalty stiffness reached [Pa/m]
  LoadPathReport closure;   ///< closure stepping
  int penalty_raises = 0;
  double seconds = 0;
};

struct SurgeryResult
{
  meshes::IncisionGeometry incision;
  double volume_pre = 0;        ///< neutral volume before surgery, full breast [m^3]
  double volume_remaining = 0;  ///< neutral volume of the remaining body, full breast [m^3]
  double resected_volume = 0;   ///< full breast [m^3]: volume_pre - volume_remaining
  double resected_volume_mesh = 0; ///< full breast [m^3], from the mesh of the resected part
  double cap_volume = 0;        ///< exact volume of the neutral cap, full breast [m^3]
  MeshQuality quality_pre, quality_incised, quality_resected;
  std::array<double, 3> new_nipple_neutral{}; ///< A after suturing (new reference)
  SutureReport suture;
  std::vector<PostureResult> pre, post;
  double seconds_mesh = 0, seconds_pre = 0, seconds_post = 0;
};


/// Where a deformation is closest to folding: the smallest det F at any
/// inversion check point (forms/geometry_forms.py: P1 vertices, P2 the
/// volume quadrature points), det F at that cell's centroid and the
/// centroid of its corners [m] (collective).
struct FoldSite
{
  double det_min = 0;
  double det_centroid = 0;
  std::array<double, 3> x{};
};
FoldSite fold_site(Model& model);

/// Close the incision of a model whose mesh has the suture tags: closure
/// stepping without gravity, then the penalty is raised x10 until the
/// largest gap is at most c's surgery.max_gap. Throws SolveError on failure,
/// naming the fold site (fold_site) and the nearest incision point.
SutureReport close_sutures(Model& model, const Config& c);
/// Largest distance of the suture faces' nodes to their target planes.
double max_suture_gap(const Model& model);

class OutputDir;

/// The steps after the sutures, shared by the cap's and the full breast's
/// surgery: the post-operative postures of `post` from its new reference
/// (r.post, r.seconds_post; probed at r.new_nipple_neutral), then
/// summary.json (`summary`, made after them), case.resolved.toml, the
/// pictures and the 3D page; commits `dir`. Progress after the share
/// (2 + postures) / stages, as surgery() places its stages.
void finish_surgery(Model& post, const Config& c, OutputDir& dir, SurgeryResult& r,
                    const std::function<nlohmann::json()>& summary, const Progress& progress,
                    double postures, double stages, MPI_Comm comm);

/// The whole surgery job; writes into `out` (replaced only on success).
/// `progress`: meshing, each pre-operative posture, the sutures, each
/// post-operative posture, the pictures (2 N + 3 stages of equal share), finished.
SurgeryResult surgery(const Config& c, const OutputTarget& out, MPI_Comm comm, const Progress& progress = {});
std::string surgery_table(const SurgeryResult& r);
nlohmann::json to_json(const SurgeryResult& r);
} // namespace breastsim
