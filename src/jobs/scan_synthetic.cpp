// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_synthetic.hpp"
#include "breastsim_registry.hpp"
#include "errors.hpp"
#include "model_setup.hpp"
#include "msh_writer.hpp"
#include "observables.hpp"
#include "output.hpp"
#include "posture_solve.hpp"
#include "reference_reset.hpp"
#include "scan_mesh.hpp"
#include "solver_options.hpp"
#include <algorithm>
#include <dolfinx/common/IndexMap.h>
#include <fmt/format.h>
#include <random>

namespace breastsim
{
using scan::operator+; // Vec3 arithmetic (std::array: no argument-dependent lookup)
using scan::operator-;
using scan::operator*;
namespace
{
using scan::Vec3;

/// The deformed position x + u of every node, in the TaggedMesh's numbering (one rank).
std::vector<Vec3> deformed_nodes(const Model& model, std::size_t num_nodes)
{
  const auto& g = model.mesh().mesh->geometry();
  const auto blocks = node_dof_blocks(model);
  const auto u = model.displacement()->x()->array();
  std::vector<Vec3> x(num_nodes);
  for (std::size_t i = 0; i < blocks.size(); ++i)
    for (int k = 0; k < 3; ++k)
      x[g.input_global_indices()[i]][k] = g.x()[3 * i + k] + (blocks[i] >= 0 ? u[3 * blocks[i] + k] : 0.0);
  return x;
}

/// The skin triangles (corner nodes) at positions `x`, each split into four at its edge midpoints.
scan::ScanSurface skin_surface(const meshes::TaggedMesh& m, const std::vector<Vec3>& x)
{
  scan::ScanSurface s;
  std::map<std::int64_t, std::int64_t> corner;
  std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> middle;
  auto node = [&](std::int64_t n)
  {
    auto [it, fresh] = corner.try_emplace(n, static_cast<std::int64_t>(s.points.size()));
    if (fresh)
      s.points.push_back(x[n]);
    return it->second;
  };
  auto mid = [&](std::int64_t a, std::int64_t b)
  {
    auto [it, fresh] = middle.try_emplace({std::min(a, b), std::max(a, b)}, static_cast<std::int64_t>(s.points.size()));
    if (fresh)
      s.points.push_back(0.5 * (x[a] + x[b]));
    return it->second;
  };
  const std::size_t npf = m.nodes_per_facet();
  for (std::size_t f = 0; f < m.facet_tags.size(); ++f)
  {
    if (m.facet_tags[f] != generated::tag("skin"))
      continue;
    const std::int64_t a = m.facets[f * npf], b = m.facets[f * npf + 1], c = m.facets[f * npf + 2];
    const std::int64_t A = node(a), B = node(b), C = node(c), ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
    for (scan::Triangle t : {scan::Triangle{A, ab, ca}, {ab, B, bc}, {ca, bc, C}, {ab, bc, ca}})
      s.triangles.push_back(t);
  }
  return s;
}

/// Remove the triangles within `radius` of `holes` random points of height
/// above a third of the top (away from the footprint), then unused points.
void cut_holes(scan::ScanSurface& s, int holes, double radius, std::mt19937& rng)
{
  double top = 0;
  for (const Vec3& p : s.points)
    top = std::max(top, p[1]);
  std::vector<Vec3> centres;
  std::uniform_int_distribution<std::size_t> pick(0, s.points.size() - 1);
  for (int tries = 0; static_cast<int>(centres.size()) < holes && tries < 10000; ++tries)
  {
    const Vec3 c = s.points[pick(rng)];
    bool apart = c[1] > top / 3;
    for (const Vec3& o : centres)
      apart = apart && scan::norm(c - o) > 4 * radius;
    if (apart)
      centres.push_back(c);
  }
  std::vector<scan::Triangle> kept;
  for (const scan::Triangle& t : s.triangles)
  {
    const Vec3 g = (1.0 / 3) * (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]);
    bool keep = true;
    for (const Vec3& c : centres)
      keep = keep && scan::norm(g - c) > radius;
    if (keep)
      kept.push_back(t);
  }
  std::vector<std::int64_t> index(s.points.size(), -1);
  scan::ScanSurface out{{}, {}, s.where, s.units};
  for (scan::Triangle t : kept)
  {
    for (auto& v : t)
    {
      if (index[v] < 0)
      {
        index[v] = static_cast<std::int64_t>(out.points.size());
        out.points.push_back(s.points[v]);
      }
      v = index[v];
    }
    out.triangles.push_back(t);
  }
  s = out;
}

/// Each point moved along its normal (the area-weighted mean of its
/// triangles' normals) by Gaussian noise of standard deviation `sigma`: the
/// depth noise of a scanner.
void add_normal_noise(scan::ScanSurface& s, double sigma, std::mt19937& rng)
{
  std::vector<Vec3> normal(s.points.size(), Vec3{0, 0, 0});
  for (const scan::Triangle& t : s.triangles)
  {
    const Vec3 n = scan::cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]);
    for (auto v : t)
      normal[v] = normal[v] + n;
  }
  std::normal_distribution<double> noise(0.0, sigma);
  for (std::size_t i = 0; i < s.points.size(); ++i)
    if (const double len = scan::norm(normal[i]); len > 0)
      s.points[i] = s.points[i] + (noise(rng) / len) * normal[i];
}

/// The true chest wall: the square |x|, |z| <= half of the plane y = 0,
/// triangles facing the breast (+y), as a second surface for --chest.
scan::ScanSurface chest_patch(double half)
{
  scan::ScanSurface c;
  const int n = 10;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      c.points.push_back({-half + 2 * half * i / n, 0.0, -half + 2 * half * j / n});
  auto id = [&](int i, int j) { return static_cast<std::int64_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) // (a, c, b): (c - a) x (b - a) along +y for a = (i, j), b = (i + 1, j)
    {
      c.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
      c.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
    }
  return c;
}

std::string extension(scan::ScanFormat f)
{
  return f == scan::ScanFormat::obj ? "obj" : (f == scan::ScanFormat::ply_ascii || f == scan::ScanFormat::ply_binary) ? "ply" : "stl";
}
} // namespace

SyntheticPatientResult synthetic_patient(const Config& material, const SyntheticPatientRequest& r,
                                         const OutputTarget& out, MPI_Comm comm)
{
  if (dolfinx::MPI::size(comm) != 1)
    throw InputError("synthetic-patient runs on one MPI rank (run it without mpirun)");
  const scan::RadialSurface ref = scan::synthetic_reference(r.shape);
  Vec3 top{0, 0, 0}; // the most anterior point of the plane x = 0: the nipple
  for (int k = 0; k <= 400; ++k)
    if (const Vec3 x = ref.point(0, -1 + k / 200.0); x[1] > top[1])
      top = x;
  const int order = static_cast<int>(material.integer("geometry.order"));
  const scan::ScanMesh mesh = scan::mesh_scan(ref, top, {r.mesh_size, order, false}, generated::tag("base"),
                                              generated::tag("skin"), generated::tag("symmetry"));
  OutputDir dir(out, comm);
  meshes::write_msh22(mesh.mesh, {{generated::tag("base"), "base"}, {generated::tag("skin"), "skin"}},
                      dir.path() / "reference.msh");
  Config c = material;
  c.set("geometry.mesh_file", (dir.path() / "reference.msh").string());
  c.set("geometry.H", mesh.nipple[1]);
  c.set("geometry.nipple_z", mesh.nipple[2]);
  c.set("geometry.mesh_size", r.mesh_size);
  c.set("postures.names", std::vector<std::string>{});
  c.set("postures.theta_deg", std::vector<double>{r.posture.theta_deg});
  auto model = make_neutral_model(c, comm);
  NewtonSolver newton(*model, NewtonOptions::from(c));
  const ObservableProbe probe(*model, mesh.nipple);
  const PostureResult loaded = solve_posture(*model, newton, probe, r.posture, c);

  std::mt19937 rng(r.seed);
  scan::ScanSurface s = skin_surface(mesh.mesh, deformed_nodes(*model, mesh.mesh.num_nodes()));
  cut_holes(s, r.holes, r.hole_radius, rng);
  add_normal_noise(s, r.noise, rng);
  for (Vec3& p : s.points)
    p = p + r.offset;
  SyntheticPatientResult res{mesh.volume, mesh.nipple, loaded.observables.nipple, s.points.size(),
                             r.points_only ? 0 : s.triangles.size(), "scan." + extension(r.format)};
  scan::write_scan(s, dir.path() / res.scan_file, r.format, scan::Units::mm, r.points_only);
  double extent = 0;
  for (std::size_t n = 0; n < mesh.mesh.num_nodes(); ++n)
    extent = std::max({extent, std::abs(mesh.mesh.x[3 * n]), std::abs(mesh.mesh.x[3 * n + 2])});
  scan::ScanSurface chest = chest_patch(1.3 * extent);
  for (Vec3& p : chest.points)
    p = p + r.offset;
  scan::write_scan(chest, dir.path() / "chest.stl", scan::ScanFormat::stl_binary, scan::Units::mm);
  c.set("geometry.mesh_file", std::string("reference.msh"));
  write_text(dir.path() / "case.reference.toml", c.to_toml(), comm);
  const auto& sh = r.shape;
  write_json(dir.path() / "truth.json",
             {{"volume_m3", sh.volume}, {"ptosis", sh.ptosis}, {"lateral", sh.lateral}, {"asymmetry", sh.asymmetry},
              {"aspect", sh.aspect}, {"mesh_volume_m3", mesh.volume}, {"posture", r.posture.name},
              {"theta_deg", r.posture.theta_deg}, {"noise_m", r.noise}, {"holes", r.holes},
              {"hole_radius_m", r.hole_radius}, {"seed", r.seed}, {"scanner_offset_m", r.offset},
              {"scan_file", res.scan_file}, {"scan_units", "mm"}, {"nipple_reference_m", mesh.nipple},
              {"loaded", to_json(loaded.observables)}},
             comm);
  dir.commit();
  return res;
}
} // namespace breastsim
