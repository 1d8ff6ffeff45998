// SPDX-License-Identifier: LGPL-3.0-or-later
#include "partner_field.hpp"
#include "mesh_from_gmsh.hpp"
#include "ghosted_assembly.hpp"
#include "errors.hpp"
#include <algorithm>
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/Geometry.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/Topology.h>
#include <fmt/format.h>
#include <limits>

namespace breastsim
{
using namespace dolfinx;

namespace
{
/// How far reference point xi lies outside the reference tetrahedron
/// (0 inside): max(0, -xi_0, -xi_1, -xi_2, xi_0 + xi_1 + xi_2 - 1).
double outside(const std::array<double, 3>& xi)
{
  return std::max({0.0, -xi[0], -xi[1], -xi[2], xi[0] + xi[1] + xi[2] - 1});
}

/// How far outside its nearest cell of face B (in that cell's reference
/// coordinates, outside()) an image g(X_i) may lie: u there is the cell's
/// polynomial extended (two faces that are mirror images only up to the
/// skin's asymmetry, e.g. the keel faces of a full breast).
constexpr double max_extension = 0.5;

/// The case-file key of the UFL Constant `name` (the name if it has none).
std::string key_of(const std::string& name)
{
  for (const auto& p : generated::parameters())
    if (p.name == name && !p.key.empty())
      return "'" + p.key + "'";
  return "'" + name + "'";
}

/// This rank's facets of face A and of face B; InputError naming the term
/// (on every rank) if either face has no facet on any rank (collective).
std::array<std::vector<std::int32_t>, 2> partner_faces(const mesh::MeshTags<std::int32_t>& facets,
                                                       const generated::PartnerInfo& info, MPI_Comm comm)
{
  const int tag_a = generated::tag(info.face_a), tag_b = generated::tag(info.face_b);
  auto faces_a = tagged_facets(facets, tag_a), faces_b = tagged_facets(facets, tag_b);
  std::array<std::int64_t, 2> counts = {static_cast<std::int64_t>(faces_a.size()),
                                        static_cast<std::int64_t>(faces_b.size())};
  MPI_Allreduce(MPI_IN_PLACE, counts.data(), 2, MPI_INT64_T, MPI_SUM, comm);
  if (counts[0] == 0 || counts[1] == 0)
    throw InputError(fmt::format("energy term '{}': the mesh has no facets tagged {} (face A = {} ({}): {} "
                                 "facets, face B = {} ({}): {} facets); tag the two faces to sew",
                                 info.term, counts[0] == 0 ? info.face_a : info.face_b, info.face_a,
                                 tag_a, counts[0], info.face_b, tag_b, counts[1]));
  return {std::move(faces_a), std::move(faces_b)};
}

/// The cells touching face B, gathered on every rank (the face is small):
/// their geometry nodes and the global (blocked) dofs of u at those nodes,
/// with bounding boxes [min x, min y, min z, max x, max y, max z].
struct FaceCells
{
  std::size_t nodes_per_cell = 0;
  std::vector<double> x;          ///< (cells, nodes_per_cell, 3)
  std::vector<std::int64_t> dofs; ///< (cells, nodes_per_cell) global node (block) indices
  std::vector<std::array<double, 6>> boxes;
  double pad = 0; ///< boxes widened by this: curved (P2) faces may put g(X_i) just outside

  std::size_t size() const { return boxes.size(); }
  /// Whether y lies in the padded box of cell k.
  bool near(std::size_t k, const std::array<double, 3>& y) const
  {
    const auto& b = boxes[k];
    return !(y[0] < b[0] - pad || y[1] < b[1] - pad || y[2] < b[2] - pad || y[0] > b[3] + pad
             || y[1] > b[4] + pad || y[2] > b[5] + pad);
  }
};

/// All ranks' values of `local` concatenated in rank order (collective).
template <typename V>
std::vector<V> all_gather(const std::vector<V>& local, MPI_Datatype type, MPI_Comm comm)
{
  int size;
  MPI_Comm_size(comm, &size);
  int n = static_cast<int>(local.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<V> all(offsets[size]);
  MPI_Allgatherv(local.data(), n, type, all.data(), counts.data(), offsets.data(), type, comm);
  return all;
}

/// The owned cells touching this rank's facets of face B, gathered on every rank.
FaceCells gather_face_cells(const fem::FunctionSpace& V, const std::vector<std::int32_t>& faces_b)
{
  const mesh::Mesh& mesh = *V.mesh();
  const int tdim = mesh.topology().dim();
  mesh.topology_mutable().create_connectivity(tdim - 1, tdim);
  auto f_to_c = mesh.topology().connectivity(tdim - 1, tdim);
  const std::int32_t owned = mesh.topology().index_map(tdim)->size_local();
  std::vector<std::int32_t> cells;
  for (auto f : faces_b)
    for (auto c : f_to_c->links(f))
      if (c < owned)
        cells.push_back(c);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  const auto& xdofs = mesh.geometry().dofmap();
  std::span<const double> xg = mesh.geometry().x();
  const auto& map = *V.dofmap()->index_map;
  FaceCells out;
  std::vector<double> x;
  std::vector<std::int64_t> dofs;
  for (auto c : cells)
  {
    for (auto n : xdofs.links(c))
      x.insert(x.end(), xg.begin() + 3 * n, xg.begin() + 3 * n + 3);
    auto cd = V.dofmap()->cell_dofs(c);
    std::vector<std::int32_t> local(cd.begin(), cd.end());
    std::vector<std::int64_t> global(local.size());
    map.local_to_global(local, global);
    dofs.insert(dofs.end(), global.begin(), global.end());
  }
  std::int64_t nn = cells.empty() ? 0 : static_cast<std::int64_t>(xdofs.links(cells[0]).size());
  MPI_Allreduce(MPI_IN_PLACE, &nn, 1, MPI_INT64_T, MPI_MAX, mesh.comm());
  out.nodes_per_cell = static_cast<std::size_t>(nn);
  out.x = all_gather(x, MPI_DOUBLE, mesh.comm());
  out.dofs = all_gather(dofs, MPI_INT64_T, mesh.comm());
  out.boxes.resize(out.dofs.size() / std::max<std::size_t>(1, out.nodes_per_cell));
  double diam = 0;
  for (std::size_t k = 0; k < out.boxes.size(); ++k)
  {
    auto& b = out.boxes[k];
    b = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (std::size_t n = 0; n < out.nodes_per_cell; ++n)
      for (int j = 0; j < 3; ++j)
      {
        const double v = out.x[3 * (k * out.nodes_per_cell + n) + j];
        b[j] = std::min(b[j], v);
        b[3 + j] = std::max(b[3 + j], v);
      }
    diam = std::max({diam, b[3] - b[0], b[4] - b[1], b[5] - b[2]});
  }
  out.pad = 1e-3 * diam;
  return out;
}

/// y = g(X) = G X + t for the point X = (x[0], x[1], x[2]).
std::array<double, 3> apply_map(const AffineMap& g, const double* x)
{
  std::array<double, 3> y;
  for (int r = 0; r < 3; ++r)
    y[r] = g[3 * r] * x[0] + g[3 * r + 1] * x[1] + g[3 * r + 2] * x[2] + g[9 + r];
  return y;
}

/// The gathered cell (index into FaceCells) in which y lies least outside
/// (outside() of its reference point xi; the first such cell on ties), or -1.
struct ImagePoint
{
  std::int64_t cell = -1;
  std::array<double, 3> xi{};
  double outside = std::numeric_limits<double>::infinity();
};

ImagePoint locate_image(const fem::CoordinateElement& cmap, const FaceCells& cells, const std::array<double, 3>& y,
                        bool nearest)
{
  namespace stdex = std::experimental;
  using mdspan2 = stdex::mdspan<double, stdex::dextents<std::size_t, 2>>;
  using cmdspan2 = stdex::mdspan<const double, stdex::dextents<std::size_t, 2>>;
  ImagePoint best;
  const std::size_t nn = cells.nodes_per_cell;
  for (std::size_t k = 0; k < cells.size(); ++k)
  {
    if (!nearest && !cells.near(k, y))
      continue;
    std::array<double, 3> xi{};
    try
    {
      cmap.pull_back_nonaffine(mdspan2(xi.data(), 1, 3), cmdspan2(y.data(), 1, 3),
                               cmdspan2(cells.x.data() + 3 * k * nn, nn, 3), 1e-12, 20);
    }
    catch (const std::runtime_error&)
    {
      continue; // Newton of the pull-back failed: y is far outside this cell
    }
    if (outside(xi) < best.outside)
      best = {static_cast<std::int64_t>(k), xi, outside(xi)};
  }
  return best;
}

/// An empty AIJ matrix n x n (n = nlocal on this rank) with `per_row` entries per row
/// (in the diagonal and in the off-diagonal part under MPI).
PetscMat create_interpolation_matrix(MPI_Comm comm, std::int32_t nlocal, std::size_t per_row)
{
  PetscMat P;
  PETSC_CHECK(MatCreate(comm, P.out()));
  PETSC_CHECK(MatSetSizes(P.get(), nlocal, nlocal, PETSC_DETERMINE, PETSC_DETERMINE));
  PETSC_CHECK(MatSetType(P.get(), MATAIJ));
  PETSC_CHECK(MatSeqAIJSetPreallocation(P.get(), static_cast<PetscInt>(per_row), nullptr));
  PETSC_CHECK(MatMPIAIJSetPreallocation(P.get(), static_cast<PetscInt>(per_row), nullptr,
                                                static_cast<PetscInt>(per_row), nullptr));
  return P;
}

/// Rows 3 i + c of P (i: global node index): u_c(y) = sum_j phi_j(xi) u_c(node j),
/// the element basis at xi of the cell whose global node indices are
/// `cell_dofs` (the geometry and u are Lagrange elements of the same degree:
/// local node j is the same point for both).
void set_interpolation_rows(Mat P, std::int64_t i, std::span<const std::int64_t> cell_dofs,
                            const std::vector<double>& basis)
{
  for (int c = 0; c < 3; ++c)
  {
    const PetscInt row = static_cast<PetscInt>(3 * i + c);
    for (std::size_t j = 0; j < cell_dofs.size(); ++j)
    {
      const PetscInt col = static_cast<PetscInt>(3 * cell_dofs[j] + c);
      const PetscScalar val = basis[j];
      if (val != 0.0)
        PETSC_CHECK(MatSetValues(P, 1, &row, 1, &col, &val, INSERT_VALUES));
    }
  }
}

/// The InputError for node X of face A whose image y lies in no candidate cell.
InputError unmapped_node(const generated::PartnerInfo& info, const double* X,
                         const std::array<double, 3>& y)
{
  return InputError(fmt::format(
      "energy term '{}': the map g sends the node ({:.6g}, {:.6g}, {:.6g}) m of face A ({}) to "
      "({:.6g}, {:.6g}, {:.6g}) m, which is in no cell touching face B ({}) nor within {} of one (in its "
      "reference coordinates); check the map "
      "keys {} and {}", info.term, X[0], X[1], X[2], info.face_a, y[0], y[1], y[2], info.face_b, max_extension,
      key_of(info.map_matrix), key_of(info.map_shift)));
}
/// Collective: the lowest rank's non-empty `error` thrown as an InputError on every rank.
void throw_first_error(const std::string& error, MPI_Comm comm)
{
  int rank;
  MPI_Comm_rank(comm, &rank);
  int who = error.empty() ? std::numeric_limits<int>::max() : rank;
  MPI_Allreduce(MPI_IN_PLACE, &who, 1, MPI_INT, MPI_MIN, comm);
  if (who == std::numeric_limits<int>::max())
    return;
  std::string message = error;
  int n = static_cast<int>(message.size());
  MPI_Bcast(&n, 1, MPI_INT, who, comm);
  message.resize(n);
  MPI_Bcast(message.data(), n, MPI_CHAR, who, comm);
  throw InputError(message);
}
} // namespace

Mat build_partner_interpolation(const fem::FunctionSpace& V,
                                const mesh::MeshTags<std::int32_t>& facets,
                                const generated::PartnerInfo& info, const AffineMap& g,
                                PartnerImageStats* stats)
{
  auto mesh = V.mesh();
  const auto faces = partner_faces(facets, info, mesh->comm());
  const FaceCells cells = gather_face_cells(V, faces[1]);
  const auto& cmap = mesh->geometry().cmap();
  auto dofmap = V.dofmap();
  if (mesh->topology().index_map(3)->size_local() > 0
      && dofmap->cell_dofs(0).size() != mesh->geometry().dofmap().links(0).size())
    throw std::logic_error("partner field: geometry and displacement degrees differ");

  // Rows: the owned nodes of face A (blocked dof indices), global row 3 (first + i) + c.
  const auto& map = *dofmap->index_map;
  const std::int32_t owned = map.size_local();
  const std::int64_t first = map.local_range()[0];
  const auto nodes_a = fem::locate_dofs_topological(V, mesh->topology().dim() - 1, faces[0]);
  const auto X = V.tabulate_dof_coordinates(false);
  PetscMat P = create_interpolation_matrix(mesh->comm(), owned * 3, cells.nodes_per_cell);
  std::vector<double> basis(cmap.tabulate_shape(0, 1)[2]);
  std::string error; // the first node whose image is too far from face B
  PartnerImageStats local;
  for (auto i : nodes_a)
  {
    if (i >= owned)
      continue; // its owner sets the row
    const std::array<double, 3> y = apply_map(g, &X[3 * i]);
    ImagePoint image = locate_image(cmap, cells, y, false);
    if (image.outside > 1e-3) // beyond face B's cells: the nearest cell's polynomial, extended
    {
      image = locate_image(cmap, cells, y, true);
      ++local.extended;
      local.max_outside = std::max(local.max_outside, image.outside);
    }
    if (image.outside > max_extension)
    {
      if (error.empty())
        error = unmapped_node(info, &X[3 * i], y).what();
      continue;
    }
    cmap.tabulate(0, std::span<const double>(image.xi.data(), 3), {1, 3}, basis);
    const std::size_t nn = cells.nodes_per_cell;
    set_interpolation_rows(P.get(), first + i,
                           std::span<const std::int64_t>(cells.dofs.data() + image.cell * nn, nn), basis);
  }
  throw_first_error(error, mesh->comm());
  if (stats)
  {
    MPI_Allreduce(&local.extended, &stats->extended, 1, MPI_INT64_T, MPI_SUM, mesh->comm());
    MPI_Allreduce(&local.max_outside, &stats->max_outside, 1, MPI_DOUBLE, MPI_MAX, mesh->comm());
  }
  PETSC_CHECK(MatAssemblyBegin(P.get(), MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(P.get(), MAT_FINAL_ASSEMBLY));
  return P.release();
}

PartnerField::PartnerField(generated::PartnerInfo info, std::shared_ptr<const fem::FunctionSpace> V)
    : _info(std::move(info)), _V(std::move(V)), _w(std::make_shared<fem::Function<T>>(_V))
{
  _w->name = _info.coefficient;
}

void PartnerField::set_forms(std::shared_ptr<fem::Form<T>> Ew, std::shared_ptr<fem::Form<T>> Euw,
                             std::shared_ptr<fem::Form<T>> Eww)
{
  _Ew = std::move(Ew);
  _Euw = std::move(Euw);
  _Eww = std::move(Eww);
}

void PartnerField::update(const fem::Function<T>& u, const mesh::MeshTags<std::int32_t>& facets,
                          const AffineMap& g)
{
  if (!_P || g != _map)
  {
    _P.reset();
    _P = PetscMat(build_partner_interpolation(*_V, facets, _info, g, &_stats));
    _map = g;
  }
  // w = P u
  PetscVec ux(la::petsc::create_vector_wrap(*u.x()));
  PetscVec wx(la::petsc::create_vector_wrap(*_w->x()));
  PETSC_CHECK(MatMult(_P.get(), ux.get(), wx.get()));
  _w->x()->scatter_fwd();
}

void PartnerField::add_gradient(Vec b, double s)
{
  if (!_bw)
    _bw = PetscVec(la::petsc::create_vector(*_V->dofmap()->index_map, _V->dofmap()->index_map_bs()));
  assemble_ghosted(_bw.get(), *_Ew);
  PETSC_CHECK(VecScale(_bw.get(), s));
  PETSC_CHECK(MatMultTransposeAdd(_P.get(), _bw.get(), b, b)); // b = b + P^T (s E_w)
}

namespace
{
/// A = a (a bilinear form, no constraints), the matrix created at the first call.
void assemble_into(PetscMat& A, const fem::Form<T>& a)
{
  if (!A)
    A = PetscMat(fem::petsc::create_matrix(a, "aij"));
  PETSC_CHECK(MatZeroEntries(A.get()));
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A.get(), ADD_VALUES), a, {});
  PETSC_CHECK(MatAssemblyBegin(A.get(), MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A.get(), MAT_FINAL_ASSEMBLY));
}
} // namespace

Mat PartnerField::hessian_coupling(std::span<const std::int8_t> constrained)
{
  assemble_into(_Auw, *_Euw);
  assemble_into(_Aww, *_Eww);
  PetscMat K, KT, Q;
  PETSC_CHECK(MatMatMult(_Auw.get(), _P.get(), MAT_INITIAL_MATRIX, PETSC_DEFAULT, K.out())); // E_uw P
  PETSC_CHECK(MatTranspose(K.get(), MAT_INITIAL_MATRIX, KT.out()));                          // P^T E_wu
  PETSC_CHECK(MatPtAP(_Aww.get(), _P.get(), MAT_INITIAL_MATRIX, PETSC_DEFAULT, Q.out()));    // P^T E_ww P
  PETSC_CHECK(MatAXPY(K.get(), 1.0, KT.get(), DIFFERENT_NONZERO_PATTERN));
  PETSC_CHECK(MatAXPY(K.get(), 1.0, Q.get(), DIFFERENT_NONZERO_PATTERN));
  // The constrained owned rows, by their global index (local index + first owned row).
  PetscInt r0, r1;
  PETSC_CHECK(MatGetOwnershipRange(K.get(), &r0, &r1));
  std::vector<PetscInt> rows;
  for (PetscInt i = 0; i < std::min<PetscInt>(r1 - r0, static_cast<PetscInt>(constrained.size())); ++i)
    if (constrained[i])
      rows.push_back(r0 + i);
  PETSC_CHECK(MatZeroRowsColumns(K.get(), static_cast<PetscInt>(rows.size()), rows.data(), 0.0,
                                 nullptr, nullptr));
  return K.release();
}
} // namespace breastsim
