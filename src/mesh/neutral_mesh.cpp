#include "neutral_mesh.hpp"
#include "breastsim_registry.hpp"

namespace breastsim
{
meshes::HalfCapSpec cap_spec(const Config& c)
{
  meshes::HalfCapSpec s;
  s.R = c.number("geometry.R");
  s.H = c.number("geometry.H");
  s.mesh_size = c.number("geometry.mesh_size");
  s.order = static_cast<int>(c.integer("geometry.order"));
  s.refinements = static_cast<int>(c.integer("geometry.refinements"));
  return s;
}

TaggedDolfinxMesh build_neutral_mesh(const Config& c, MPI_Comm comm)
{
  const meshes::HalfCapSpec spec = cap_spec(c);
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh m;
  m.order = spec.order;
  if (rank == 0)
    m = meshes::mesh_half_cap(spec, generated::tag("base"), generated::tag("skin"), generated::tag("symmetry"));
  return to_dolfinx(comm, m, spec.order);
}
} // namespace breastsim
