// SPDX-License-Identifier: LGPL-3.0-or-later
#include "full_breast_surgery.hpp"
#include "breastsim_registry.hpp"
#include "case_options.hpp"
#include "errors.hpp"
#include "full_breast_sutures.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "on_root.hpp"
#include "output.hpp"
#include "output_options.hpp"
#include "posture.hpp"
#include "reference_reset.hpp"
#include "skin_solid.hpp"
#include "timer.hpp"
#include "user_mesh.hpp"
#include "viewer.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <type_traits>

namespace breastsim
{
bool is_full_breast_case(const Config& c) { return !HalfCapSpec::from(c).mesh_file.empty(); }

namespace
{
/// The three meshes of a surgery.
struct FullBreastBodies
{
  TaggedDolfinxMesh pre, cut, resected;
};

/// The neutral mesh read and checked, its skin fitted, the incision built and
/// both bodies meshed (rank 0, every rank throws its InputError).
struct RootMeshes
{
  meshes::TaggedMesh neutral, kept, resected;
};

RootMeshes mesh_on_root(const Config& c, MPI_Comm comm, FullBreastSurgeryResult& r)
{
  const HalfCapSpec geo = HalfCapSpec::from(c);
  RootMeshes m;
  m.neutral.order = m.kept.order = m.resected.order = geo.order;
  double volumes[5] = {};
  on_root(comm, [&]
  {
    const int symmetry = generated::tag("symmetry");
    m.neutral = meshes::read_user_mesh(geo.mesh_file, geo.order,
                                       {generated::tag("base"), generated::tag("skin"), symmetry});
    if (std::count(m.neutral.facet_tags.begin(), m.neutral.facet_tags.end(), symmetry) > 0)
      throw InputError(fmt::format("key 'geometry.mesh_file' = '{}' is a half model (it has a \"symmetry\" group): "
                                   "surgery on a user mesh cuts the full breast; give the full breast's mesh",
                                   geo.mesh_file));
    const scan::RadialSurface fit = scan::fit_mesh_skin(m.neutral, generated::tag("skin"), &r.skin_fit_rms);
    r.incision = scan::full_incision_geometry(fit, IncisionSpec::from(c));
    const scan::FullIncisionTags tags{generated::tag("base"), generated::tag("skin"), generated::tag("suture_a"),
                                      generated::tag("suture_b"), generated::tag("suture_bcd")};
    auto cut = scan::mesh_full_incision(fit, r.incision, tags, geo.mesh_size, geo.order, geo.refinements);
    m.kept = std::move(cut.kept);
    m.resected = std::move(cut.resected);
    volumes[0] = cut.volume_solid, volumes[1] = cut.volume_kept, volumes[2] = cut.volume_resected;
    volumes[3] = r.skin_fit_rms;
    volumes[4] = cut.face_a_on_mirror ? 1 : 0;
  });
  static_assert(std::is_trivially_copyable_v<scan::FullIncisionGeometry>);
  MPI_Bcast(&r.incision, sizeof(r.incision), MPI_BYTE, 0, comm);
  MPI_Bcast(volumes, 5, MPI_DOUBLE, 0, comm);
  r.base.cap_volume = volumes[0];
  r.volume_kept_cad = volumes[1];
  r.volume_resected_cad = volumes[2];
  r.skin_fit_rms = volumes[3];
  r.face_a_on_mirror = volumes[4] != 0;
  return m;
}

FullBreastBodies mesh_full_breast_surgery(const Config& c, MPI_Comm comm, FullBreastSurgeryResult& r)
{
  Stopwatch clock("surgery: meshing");
  const int order = HalfCapSpec::from(c).order;
  RootMeshes m = mesh_on_root(c, comm, r);
  FullBreastBodies b{to_dolfinx(comm, m.neutral, order), to_dolfinx(comm, m.kept, order),
                     to_dolfinx(comm, m.resected, order)};
  r.base.seconds_mesh = clock.seconds();
  r.base.quality_pre = mesh_quality(*b.pre.mesh);
  r.base.quality_incised = mesh_quality(*b.cut.mesh);
  r.base.quality_resected = mesh_quality(*b.resected.mesh);
  const auto& g = r.incision;
  r.base.incision = {g.A, g.B, g.C, g.D, g.n1, g.c1, g.n2, g.c2};
  return b;
}

/// The named incision points (for messages).
std::vector<std::pair<std::string, std::array<double, 3>>> incision_points(const scan::FullIncisionGeometry& g)
{
  return {{"A", g.A}, {"B", g.B}, {"B'", g.B_mirror}, {"C", g.C}, {"D", g.D}, {"D'", g.D_mirror}};
}

/// Sutures (no gravity) of the remaining body `post`, then its final neutral
/// state (the new reference); fields into `dir`.
void suture_full_breast(Model& post, const Config& c, const std::filesystem::path& dir, FullBreastSurgeryResult& r)
{
  const OutputOptions output = OutputOptions::from(c);
  r.base.volume_remaining = post.volume();
  r.base.resected_volume = r.base.volume_pre - r.base.volume_remaining;
  log::info("surgery: resected volume {:.1f} cm^3 (full breast); closing the sutures", 1e6 * r.base.resected_volume);
  write_fields(post, dir / "incised_neutral", output.xdmf, false);
  const FullSutureReport sutures = close_full_breast_sutures(post, c, incision_points(r.incision));
  r.base.suture = sutures.suture;
  r.gap_tissue = sutures.gap_tissue;
  r.gap_chest = sutures.gap_chest;
  r.keel_images = sutures.images;
  write_fields(post, dir / "sutured", output.xdmf, output.vtk);
  r.base.new_nipple_neutral = ObservableProbe(post, r.incision.A).measure(post).nipple;
  reset_reference(post);
  // The knitted faces now hold their sutured positions: both closures 0.
  post.set_parameter("closure", {0.0});
  post.set_parameter("tissue_closure", {0.0});
  write_fields(post, dir / "final_neutral", output.xdmf, false);
}
} // namespace

FullBreastSurgeryResult full_breast_surgery(const Config& c, const OutputTarget& out, MPI_Comm comm,
                                            const Progress& progress)
{
  FullBreastSurgeryResult r;
  // Stages: meshing, pre-op postures, sutures, post-op postures (and the pictures).
  const double postures = static_cast<double>(requested_postures(c).size()),
               stages = 2 * postures + 2 + (OutputOptions::from(c).pictures_on() ? 1 : 0);
  const CaseOptions case_options = CaseOptions::from(c);
  if (OutputOptions::from(c).pictures_on())
    check_picture_tools(comm);
  progress.report("meshing", 0);
  FullBreastBodies bodies = mesh_full_breast_surgery(c, comm, r); // refuses bad incisions first
  OutputDir dir(out, comm);
  std::filesystem::create_directories(dir.path() / "preop");
  std::filesystem::create_directories(dir.path() / "postop");
  {
    Model res(bodies.resected, Constraints{false, false});
    r.base.resected_volume_mesh = res.volume();
    if (OutputOptions::from(c).xdmf)
      write_mesh_xdmf(bodies.resected, dir.path() / "resected.xdmf");
  }
  {
    Stopwatch clock("surgery: pre-operative postures");
    Model pre(bodies.pre, Constraints{false, case_options.fixed_base});
    apply_parameters(c, pre);
    r.base.volume_pre = pre.volume();
    log::info("surgery: pre-operative postures (full breast)");
    r.base.pre = solve_postures(pre, ObservableProbe(pre, case_options.geometry.nipple()), c, dir.path() / "preop",
                                nullptr, progress.part(1 / stages, (1 + postures) / stages, "pre-operative "));
    r.base.seconds_pre = clock.seconds();
  }
  Model post(bodies.cut, Constraints{false, case_options.fixed_base});
  apply_parameters(c, post);
  progress.report("sutures", (1 + postures) / stages);
  suture_full_breast(post, c, dir.path(), r);
  finish_surgery(post, c, dir, r.base, [&] { return to_json(r); }, progress, postures, stages, comm);
  return r;
}

nlohmann::json to_json(const FullBreastSurgeryResult& r)
{
  nlohmann::json j = to_json(r.base);
  const auto& g = r.incision;
  j["model"] = "full breast";
  j["incision"]["B_mirror_m"] = g.B_mirror;
  j["incision"]["D_mirror_m"] = g.D_mirror;
  j["incision"]["P1_mirror_normal"] = g.n1_mirror;
  j["skin_fit_rms_m"] = r.skin_fit_rms;
  j["suture"]["face_a"] = r.face_a_on_mirror ? "P1' (x < 0)" : "P1 (x > 0)";
  j["solid_volume_m3"] = r.base.cap_volume;
  j["volume_remaining_cad_m3"] = r.volume_kept_cad;
  j["resected_volume_cad_m3"] = r.volume_resected_cad;
  j["suture"]["max_gap_keel_m"] = r.gap_tissue;
  j["suture"]["max_gap_chest_m"] = r.gap_chest;
  j["suture"]["keel_nodes_extended"] = r.keel_images.extended;
  j["suture"]["keel_max_extension"] = r.keel_images.max_outside;
  return j;
}
} // namespace breastsim
