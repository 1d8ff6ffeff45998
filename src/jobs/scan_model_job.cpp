// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_model_job.hpp"
#include "breastsim_registry.hpp"
#include "mesh_from_gmsh.hpp"
#include "msh_writer.hpp"
#include "on_root.hpp"
#include "output.hpp"
#include <cmath>
#include <fmt/format.h>

namespace breastsim
{
namespace
{
nlohmann::json frame_json(const scan::BreastFrame& f, scan::Units units)
{
  return {{"description", "x_scanner = origin + X * e_x + Y * e_y + Z * e_z (metres; the scan's file was in "
                          "the stated unit and is scaled by unit_to_m); breast frame: y the outward chest normal, "
                          "z cranial, x lateral, origin on the chest plane in the nipple's sagittal plane"},
          {"origin_m", f.origin}, {"e_x", f.ex}, {"e_y", f.ey}, {"e_z", f.ez},
          {"mirrored", f.mirrored()}, {"unit_to_m", units == scan::Units::mm ? 1e-3 : 1.0}};
}

nlohmann::json summary_json(const scan::ScanModel& m, std::size_t cells, const Posture& p)
{
  return {{"posture", p.name}, {"theta_deg", p.theta_deg}, {"scan_points", m.points},
          {"scan_triangles", m.triangles}, {"points_fitted", m.points_used},
          {"fit_degree", m.fit.degree}, {"fit_rms_m", m.fit_rms}, {"noise_rms_m", m.noise_rms},
          {"nipple_m", m.mesh.nipple}, {"footprint_radius_m", m.frame.footprint_radius},
          {"footprint_off_plane_m", m.frame.footprint_off_plane}, {"chest", chest_json(m.chest)},
          {"tetrahedra", cells}, {"nodes", m.mesh.mesh.num_nodes()},
          {"volume_m3", m.half ? 2 * m.mesh.volume : m.mesh.volume}};
}
} // namespace

nlohmann::json chest_json(const scan::ChestCurvature& c)
{
  nlohmann::json j = {{"source", c.source}, {"samples", c.samples}, {"plane_rms_m", c.plane_rms},
                      {"plane_max_m", c.plane_max}, {"base", "the chest plane (a planar base)"}};
  if (c.quadric)
  {
    j["quadric_rms_m"] = c.quadric_rms;
    j["curvature_radii_m"] = nlohmann::json::array();
    for (double r : c.curvature_radii)
      j["curvature_radii_m"].push_back(std::isfinite(r) ? nlohmann::json(r) : nlohmann::json(nullptr));
  }
  return j;
}

Config scan_case(const scan::ScanModel& m, const std::string& mesh_file, const Posture& posture,
                 const std::string& name)
{
  Config c;
  c.set("case.name", name);
  c.set("geometry.mesh_file", mesh_file);
  c.set("geometry.H", m.mesh.nipple[1]);
  c.set("geometry.nipple_z", m.mesh.nipple[2]);
  c.set("geometry.R", m.frame.footprint_radius);
  c.set("geometry.mesh_size", m.mesh_size);
  c.set("geometry.order", std::int64_t(m.mesh.mesh.order));
  const bool named = posture.name == "standing" || posture.name == "supine" || posture.name == "all_fours" ||
                     posture.name == "prone";
  c.set("postures.names", named ? std::vector<std::string>{posture.name} : std::vector<std::string>{});
  c.set("postures.theta_deg", named ? std::vector<double>{} : std::vector<double>{posture.theta_deg});
  return c;
}

ScanModelResult scan_model(const ScanModelRequest& r, const OutputTarget& out, MPI_Comm comm)
{
  ScanModelResult res;
  on_root(comm, [&] { // every rank throws rank 0's InputError
    res.model = scan::build_scan_model(r.skin, r.chest, r.options, generated::tag("base"), generated::tag("skin"),
                                       generated::tag("symmetry"));
    res.cells = res.model.mesh.mesh.num_cells();
  });
  std::string toml;
  if (rank_of(comm) == 0)
  {
    const Config c = scan_case(res.model, "scan.msh", r.posture, r.name);
    toml = fmt::format("# breastsim scan-model: the scan '{}' recorded {} (theta = {} deg), in the breast frame\n"
                       "# (frame.json maps it back to the scanner's frame). Its stress-free state:\n"
                       "#   breastsim neutral-state case.toml --posture {}\n",
                       r.skin.string(), r.posture.name, r.posture.theta_deg, r.posture.name) + c.to_toml();
  }
  OutputDir dir(out, comm);
  if (rank_of(comm) == 0)
  {
    std::map<int, std::string> names = {{generated::tag("base"), "base"}, {generated::tag("skin"), "skin"}};
    if (r.options.mesh.half)
      names[generated::tag("symmetry")] = "symmetry";
    meshes::write_msh22(res.model.mesh.mesh, names, dir.path() / "scan.msh");
  }
  write_text(dir.path() / "case.toml", toml, comm);
  int order = res.model.mesh.mesh.order; // known on rank 0
  MPI_Bcast(&order, 1, MPI_INT, 0, comm);
  write_mesh_xdmf(to_dolfinx(comm, res.model.mesh.mesh, order), dir.path() / "scan.xdmf");
  write_json(dir.path() / "frame.json", frame_json(res.model.frame, r.options.units), comm);
  write_json(dir.path() / "summary.json", summary_json(res.model, res.cells, r.posture), comm);
  dir.commit();
  res.model.mesh.mesh = {};
  return res;
}

std::string scan_model_table(const ScanModelResult& r)
{
  const scan::ScanModel& m = r.model;
  return fmt::format("scan: {} points, {} triangles; fit degree {}: RMS {:.3f} mm, noise {:.3f} mm (robust)\n"
                     "footprint radius {:.1f} mm; nipple ({:.1f}, {:.1f}, {:.1f}) mm; {} tetrahedra, volume {:.1f} cm3\n",
                     m.points, m.triangles, m.fit.degree, 1e3 * m.fit_rms, 1e3 * m.noise_rms,
                     1e3 * m.frame.footprint_radius, 1e3 * m.mesh.nipple[0], 1e3 * m.mesh.nipple[1],
                     1e3 * m.mesh.nipple[2], r.cells, 1e6 * (m.half ? 2 : 1) * m.mesh.volume);
}
} // namespace breastsim
