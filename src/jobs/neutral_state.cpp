// SPDX-License-Identifier: LGPL-3.0-or-later
#include "neutral_state.hpp"
#include "breastsim_registry.hpp"
#include "case_options.hpp"
#include "half_cap.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "msh_writer.hpp"
#include "output.hpp"
#include "output_options.hpp"
#include "solver_options.hpp"
#include "user_mesh.hpp"
#include <dolfinx/common/IndexMap.h>
#include "errors.hpp"
#include "on_root.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace breastsim
{
namespace
{
/// The case's geometry as a TaggedMesh (the user's mesh or the cap; call on one rank).
meshes::TaggedMesh root_mesh(const HalfCapSpec& spec)
{
  const int base = generated::tag("base"), skin = generated::tag("skin"), sym = generated::tag("symmetry");
  return spec.mesh_file.empty() ? meshes::mesh_half_cap(spec, base, skin, sym)
                                : meshes::read_user_mesh(spec.mesh_file, spec.order, {base, skin, sym});
}

/// The case of the reference: its mesh file and nipple.
Config reference_case(const Config& c, const std::array<double, 3>& nipple)
{
  Config r = c;
  r.set("geometry.mesh_file", std::string("reference.msh"));
  r.set("geometry.H", nipple[1]);
  r.set("geometry.nipple_z", nipple[2]);
  r.set("geometry.refinements", std::int64_t(0));
  return r;
}

/// The reference's tetrahedra keep their orientation: signed corner volume
/// (b - a) . ((c - a) x (d - a)) / 6 > 0; else SolveError naming the cell.
void check_reference_cells(const meshes::TaggedMesh& m)
{
  const std::size_t npc = m.nodes_per_cell();
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    std::array<std::array<double, 3>, 4> p;
    for (int k = 0; k < 4; ++k)
      for (int i = 0; i < 3; ++i)
        p[k][i] = m.x[3 * m.cells[c * npc + k] + i];
    auto d = [&](int k, int i) { return p[k][i] - p[0][i]; };
    const double v = (d(1, 0) * (d(2, 1) * d(3, 2) - d(2, 2) * d(3, 1)) - d(1, 1) * (d(2, 0) * d(3, 2) - d(2, 2) * d(3, 0)) +
                      d(1, 2) * (d(2, 0) * d(3, 1) - d(2, 1) * d(3, 0))) / 6;
    if (!(v > 0))
      throw SolveError(fmt::format("inverse neutral state: the reference found folds: tetrahedron {} near ({:.1f}, "
                                   "{:.1f}, {:.1f}) mm is inverted (volume {:.3g} mm^3); no stress-free body of this "
                                   "mesh deforms into the shape (a finer mesh, or a shape the material can hold)",
                                   c, 1e3 * p[0][0], 1e3 * p[0][1], 1e3 * p[0][2], 1e9 * v));
  }
}

/// Names of the surfaces the loaded mesh has (a full breast has no symmetry face).
std::map<int, std::string> surface_names(const meshes::TaggedMesh& m)
{
  std::map<int, std::string> names;
  for (const char* n : {"base", "skin", "symmetry"})
    if (std::count(m.facet_tags.begin(), m.facet_tags.end(), generated::tag(n)) > 0)
      names[generated::tag(n)] = n;
  return names;
}

nlohmann::json to_json(const NeutralStateResult& r)
{
  nlohmann::json it = nlohmann::json::array();
  for (const auto& i : r.inverse.iterations)
    it.push_back({{"mismatch_rms_m", i.rms_mismatch}, {"mismatch_max_m", i.max_mismatch},
                  {"omega", i.omega}, {"newton_iterations", i.newton_iterations}});
  return {{"posture", r.posture.name}, {"theta_deg", r.posture.theta_deg},
          {"converged", r.inverse.converged}, {"iterations", it}, {"wall_time_s", r.inverse.seconds},
          {"nipple_neutral_m", r.nipple}, {"max_node_shift_m", r.max_node_shift},
          {"reference_shift_x_m", r.shift_x}};
}
} // namespace

NeutralStateResult neutral_state(const Config& c, const Posture& posture, const InverseOptions& o,
                                 const OutputTarget& out, MPI_Comm comm)
{
  const CaseOptions co = CaseOptions::from(c);
  meshes::TaggedMesh loaded;
  loaded.order = co.geometry.order;
  std::size_t nipple = 0;
  on_root(comm, [&] { // every rank throws rank 0's InputError
    loaded = root_mesh(co.geometry);
    nipple = nipple_node(loaded, co.geometry.mesh_file.empty() ? "the cap" : co.geometry.mesh_file,
                         co.geometry.nipple());
  });
  Model model(to_dolfinx(comm, loaded, co.geometry.order), Constraints{true, co.fixed_base});
  apply_parameters(c, model);
  NewtonSolver newton(model, SolverOptions::from(c).newton);
  const double f = set_gravity(model, gravity_vector(posture.theta_deg, co.gravity));
  NeutralStateResult r{posture, {}, {}, 0};
  r.inverse = inverse_neutral_state(model, newton, o, f);
  OutputDir dir(out, comm);
  const std::vector<double> x = gather_geometry_nodes(*model.mesh().mesh, loaded.num_nodes());
  if (rank_of(comm) == 0)
  {
    for (std::size_t i = 0; i < x.size(); ++i)
      r.max_node_shift = std::max(r.max_node_shift, std::abs(x[i] - loaded.x[i]));
    loaded.x = x;
    // A full breast (no symmetry face) may move its nipple off x = 0: the
    // reference is moved along x to keep it in the sagittal plane x = 0
    // (a rigid shift: its loaded shapes move with it).
    if (surface_names(loaded).count(generated::tag("symmetry")) == 0)
    {
      r.shift_x = -x[3 * nipple];
      for (std::size_t n = 0; n < loaded.num_nodes(); ++n)
        loaded.x[3 * n] += r.shift_x;
    }
    r.nipple = {loaded.x[3 * nipple], loaded.x[3 * nipple + 1], loaded.x[3 * nipple + 2]};
  }
  MPI_Bcast(&r.shift_x, 1, MPI_DOUBLE, 0, comm);
  std::string fold; // rank 0's SolveError, thrown on every rank
  if (rank_of(comm) == 0)
    try
    {
      check_reference_cells(loaded);
    }
    catch (const SolveError& e)
    {
      fold = e.what();
    }
  broadcast(fold, comm);
  if (!fold.empty())
    throw SolveError(fold);
  if (rank_of(comm) == 0)
    meshes::write_msh22(loaded, surface_names(loaded), dir.path() / "reference.msh");
  MPI_Bcast(r.nipple.data(), 3, MPI_DOUBLE, 0, comm);
  MPI_Bcast(&r.max_node_shift, 1, MPI_DOUBLE, 0, comm);
  write_text(dir.path() / "case.reference.toml", reference_case(c, r.nipple).to_toml(), comm);
  write_json(dir.path() / "summary.json", to_json(r), comm);
  // For ParaView: the reference (shifted like reference.msh) and the
  // displacement that carries it into the recorded shape.
  for (std::size_t n = 0; n < model.mesh().mesh->geometry().x().size(); n += 3)
    model.mesh().mesh->geometry().x()[n] += r.shift_x;
  const OutputOptions output = OutputOptions::from(c);
  write_fields(model, dir.path() / ("neutral_" + posture.name), output.xdmf, output.vtk);
  dir.commit();
  return r;
}

std::string neutral_state_table(const NeutralStateResult& r)
{
  std::string s = fmt::format("neutral state of the shape recorded {} (theta {} deg): {} iterations, "
                              "{:.1f} s\n",
                              r.posture.name, r.posture.theta_deg, r.inverse.iterations.size(),
                              r.inverse.seconds);
  for (std::size_t k = 0; k < r.inverse.iterations.size(); ++k)
  {
    const auto& i = r.inverse.iterations[k];
    s += fmt::format("  {:>3}  mismatch RMS {:10.4g} mm  max {:10.4g} mm  omega {:.3f}  Newton {}\n", k,
                     1e3 * i.rms_mismatch, 1e3 * i.max_mismatch, i.omega, i.newton_iterations);
  }
  s += fmt::format("nipple in the neutral state: ({:.2f}, {:.2f}, {:.2f}) mm; largest node shift {:.2f} mm\n",
                   1e3 * r.nipple[0], 1e3 * r.nipple[1], 1e3 * r.nipple[2], 1e3 * r.max_node_shift);
  return s;
}
} // namespace breastsim
