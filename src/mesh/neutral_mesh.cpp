// SPDX-License-Identifier: LGPL-3.0-or-later
#include "neutral_mesh.hpp"
#include "breastsim_registry.hpp"
#include "user_mesh.hpp"

namespace breastsim
{
TaggedDolfinxMesh build_neutral_mesh(const Config& c, MPI_Comm comm)
{
  const HalfCapSpec spec = HalfCapSpec::from(c);
  if (!spec.mesh_file.empty())
    return load_user_mesh(spec.mesh_file, spec.order, comm, spec.nipple());
  int rank;
  MPI_Comm_rank(comm, &rank);
  meshes::TaggedMesh m;
  m.order = spec.order;
  if (rank == 0)
    m = meshes::mesh_half_cap(spec, generated::tag("base"), generated::tag("skin"), generated::tag("symmetry"));
  return to_dolfinx(comm, m, spec.order);
}
} // namespace breastsim
