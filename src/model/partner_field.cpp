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

/// The case-file key of the UFL Constant `name` (the name if it has none).
std::string key_of(const std::string& name)
{
  for (const auto& p : generated::parameters())
    if (p.name == name && !p.key.empty())
      return "'" + p.key + "'";
  return "'" + name + "'";
}

/// Refuse more than one rank: P is built from the serial mesh.
void require_serial(MPI_Comm comm, const std::string& term)
{
  int size;
  MPI_Comm_size(comm, &size);
  if (size > 1)
    throw InputError(fmt::format("energy term '{}' (a tissue-to-tissue suture) is serial-only: run it "
                                 "with one MPI rank (got {})", term, size));
}

/// The facets of face A and of face B; InputError naming the term if either is empty.
std::array<std::vector<std::int32_t>, 2> partner_faces(const mesh::MeshTags<std::int32_t>& facets,
                                                       const generated::PartnerInfo& info)
{
  const int tag_a = generated::tag(info.face_a), tag_b = generated::tag(info.face_b);
  auto faces_a = tagged_facets(facets, tag_a), faces_b = tagged_facets(facets, tag_b);
  if (faces_a.empty() || faces_b.empty())
    throw InputError(fmt::format("energy term '{}': the mesh has no facets tagged {} (face A = {} ({}): {} "
                                 "facets, face B = {} ({}): {} facets); tag the two faces to sew",
                                 info.term, faces_a.empty() ? info.face_a : info.face_b, info.face_a,
                                 tag_a, faces_a.size(), info.face_b, tag_b, faces_b.size()));
  return {std::move(faces_a), std::move(faces_b)};
}

/// The cells touching face B, where the images g(X_i) are looked for, with
/// their bounding boxes [min x, min y, min z, max x, max y, max z].
struct CandidateCells
{
  std::vector<std::int32_t> cells;
  std::vector<std::array<double, 6>> boxes;
  double pad = 0; ///< boxes widened by this: curved (P2) faces may put g(X_i) just outside

  /// Whether y lies in the padded box of cell k.
  bool near(std::size_t k, const std::array<double, 3>& y) const
  {
    const auto& b = boxes[k];
    return !(y[0] < b[0] - pad || y[1] < b[1] - pad || y[2] < b[2] - pad || y[0] > b[3] + pad
             || y[1] > b[4] + pad || y[2] > b[5] + pad);
  }
};

CandidateCells candidate_cells(const mesh::Mesh& mesh, const std::vector<std::int32_t>& faces_b)
{
  const int tdim = mesh.topology().dim();
  mesh.topology_mutable().create_connectivity(tdim - 1, tdim);
  auto f_to_c = mesh.topology().connectivity(tdim - 1, tdim);
  CandidateCells out;
  for (auto f : faces_b)
    for (auto c : f_to_c->links(f))
      out.cells.push_back(c);
  std::sort(out.cells.begin(), out.cells.end());
  out.cells.erase(std::unique(out.cells.begin(), out.cells.end()), out.cells.end());
  const auto& xdofs = mesh.geometry().dofmap();
  std::span<const double> xg = mesh.geometry().x();
  out.boxes.resize(out.cells.size());
  double diam = 0;
  for (std::size_t k = 0; k < out.cells.size(); ++k)
  {
    auto& b = out.boxes[k];
    b = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (auto n : xdofs.links(out.cells[k]))
      for (int j = 0; j < 3; ++j)
      {
        b[j] = std::min(b[j], xg[3 * n + j]);
        b[3 + j] = std::max(b[3 + j], xg[3 * n + j]);
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

/// The candidate cell in which y lies least outside (outside() of its
/// reference point xi; the first such cell on ties), or cell -1.
struct ImagePoint
{
  std::int32_t cell = -1;
  std::array<double, 3> xi{};
  double outside = std::numeric_limits<double>::infinity();
};

ImagePoint locate_image(const mesh::Geometry& geom, const CandidateCells& candidates,
                        const std::array<double, 3>& y)
{
  namespace stdex = std::experimental;
  using mdspan2 = stdex::mdspan<double, stdex::dextents<std::size_t, 2>>;
  using cmdspan2 = stdex::mdspan<const double, stdex::dextents<std::size_t, 2>>;
  const auto& xdofs = geom.dofmap();
  std::span<const double> xg = geom.x();
  ImagePoint best;
  std::vector<double> nodes;
  for (std::size_t k = 0; k < candidates.cells.size(); ++k)
  {
    if (!candidates.near(k, y))
      continue;
    auto gn = xdofs.links(candidates.cells[k]);
    nodes.resize(3 * gn.size());
    for (std::size_t n = 0; n < gn.size(); ++n)
      for (int j = 0; j < 3; ++j)
        nodes[3 * n + j] = xg[3 * gn[n] + j];
    std::array<double, 3> xi{};
    try
    {
      geom.cmap().pull_back_nonaffine(mdspan2(xi.data(), 1, 3), cmdspan2(y.data(), 1, 3),
                                      cmdspan2(nodes.data(), gn.size(), 3), 1e-12, 20);
    }
    catch (const std::runtime_error&)
    {
      continue; // Newton of the pull-back failed: y is far outside this cell
    }
    if (outside(xi) < best.outside)
      best = {candidates.cells[k], xi, outside(xi)};
  }
  return best;
}

/// An empty AIJ matrix n x n (n = nlocal on this rank) with `per_row` entries per row.
PetscMat create_interpolation_matrix(MPI_Comm comm, std::int32_t nlocal, std::size_t per_row)
{
  PetscMat P;
  PETSC_CHECK(MatCreate(comm, P.out()));
  PETSC_CHECK(MatSetSizes(P.get(), nlocal, nlocal, PETSC_DETERMINE, PETSC_DETERMINE));
  PETSC_CHECK(MatSetType(P.get(), MATAIJ));
  PETSC_CHECK(MatSeqAIJSetPreallocation(P.get(), static_cast<PetscInt>(per_row), nullptr));
  PETSC_CHECK(MatMPIAIJSetPreallocation(P.get(), static_cast<PetscInt>(per_row), nullptr, 0, nullptr));
  return P;
}

/// Rows 3 i + c of P: u_c(y) = sum_j phi_j(xi) u_c(node j), the element basis
/// at xi of the cell with dofs `cell_dofs` (the geometry and u are Lagrange
/// elements of the same degree: local node j is the same point for both).
void set_interpolation_rows(Mat P, std::int32_t i, std::span<const std::int32_t> cell_dofs,
                            const std::vector<double>& basis)
{
  for (int c = 0; c < 3; ++c)
  {
    const PetscInt row = 3 * i + c;
    for (std::size_t j = 0; j < cell_dofs.size(); ++j)
    {
      const PetscInt col = 3 * cell_dofs[j] + c;
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
      "({:.6g}, {:.6g}, {:.6g}) m, which is in no cell touching face B ({}); check the map "
      "keys {} and {}", info.term, X[0], X[1], X[2], info.face_a, y[0], y[1], y[2], info.face_b,
      key_of(info.map_matrix), key_of(info.map_shift)));
}
} // namespace

Mat build_partner_interpolation(const fem::FunctionSpace& V,
                                const mesh::MeshTags<std::int32_t>& facets,
                                const generated::PartnerInfo& info, const AffineMap& g)
{
  auto mesh = V.mesh();
  require_serial(mesh->comm(), info.term);
  const auto faces = partner_faces(facets, info);
  const CandidateCells candidates = candidate_cells(*mesh, faces[1]);
  const auto& geom = mesh->geometry();
  const std::size_t nn = geom.dofmap().links(candidates.cells[0]).size();
  auto dofmap = V.dofmap();
  if (static_cast<std::size_t>(dofmap->cell_dofs(candidates.cells[0]).size()) != nn)
    throw std::logic_error("partner field: geometry and displacement degrees differ");

  // Rows: the nodes of face A (blocked dof indices).
  const auto nodes_a = fem::locate_dofs_topological(V, mesh->topology().dim() - 1, faces[0]);
  const auto X = V.tabulate_dof_coordinates(false);
  PetscMat P = create_interpolation_matrix(mesh->comm(), dofmap->index_map->size_local() * 3, nn);
  std::vector<double> basis(geom.cmap().tabulate_shape(0, 1)[2]);
  for (auto i : nodes_a)
  {
    const std::array<double, 3> y = apply_map(g, &X[3 * i]);
    const ImagePoint image = locate_image(geom, candidates, y);
    if (image.outside > 1e-3)
      throw unmapped_node(info, &X[3 * i], y);
    geom.cmap().tabulate(0, std::span<const double>(image.xi.data(), 3), {1, 3}, basis);
    set_interpolation_rows(P.get(), i, dofmap->cell_dofs(image.cell), basis);
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
    _P = PetscMat(build_partner_interpolation(*_V, facets, _info, g));
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
  std::vector<PetscInt> rows;
  for (std::size_t i = 0; i < constrained.size(); ++i)
    if (constrained[i])
      rows.push_back(static_cast<PetscInt>(i));
  PETSC_CHECK(MatZeroRowsColumns(K.get(), static_cast<PetscInt>(rows.size()), rows.data(), 0.0,
                                 nullptr, nullptr));
  return K.release();
}
} // namespace breastsim
