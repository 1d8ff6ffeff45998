#include "partner_field.hpp"
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
std::vector<std::int32_t> facets_with(const mesh::MeshTags<std::int32_t>& tags, int value)
{
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < tags.values().size(); ++i)
    if (tags.values()[i] == value)
      out.push_back(tags.indices()[i]);
  return out;
}

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

void destroy(Mat& A)
{
  if (A)
    MatDestroy(&A);
  A = nullptr;
}
} // namespace

Mat build_partner_interpolation(const fem::FunctionSpace& V,
                                const mesh::MeshTags<std::int32_t>& facets,
                                const generated::PartnerInfo& info, const AffineMap& g)
{
  const std::string& term = info.term;
  const int tag_a = generated::tag(info.face_a), tag_b = generated::tag(info.face_b);
  auto mesh = V.mesh();
  const MPI_Comm comm = mesh->comm();
  int size;
  MPI_Comm_size(comm, &size);
  if (size > 1)
    throw InputError(fmt::format("energy term '{}' (a tissue-to-tissue suture) is serial-only: run it "
                                 "with one MPI rank (got {})", term, size));
  auto& topology = mesh->topology();
  const int tdim = topology.dim();
  mesh->topology_mutable().create_connectivity(tdim - 1, tdim);
  auto f_to_c = topology.connectivity(tdim - 1, tdim);
  const auto faces_a = facets_with(facets, tag_a), faces_b = facets_with(facets, tag_b);
  if (faces_a.empty() || faces_b.empty())
    throw InputError(fmt::format("energy term '{}': the mesh has no facets tagged {} (face A = {} ({}): {} "
                                 "facets, face B = {} ({}): {} facets); tag the two faces to sew",
                                 term, faces_a.empty() ? info.face_a : info.face_b, info.face_a, tag_a,
                                 faces_a.size(), info.face_b, tag_b, faces_b.size()));

  // Candidate cells: those touching face B, with their bounding boxes.
  std::vector<std::int32_t> cells;
  for (auto f : faces_b)
    for (auto c : f_to_c->links(f))
      cells.push_back(c);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  const auto& geom = mesh->geometry();
  const auto& xdofs = geom.dofmap();
  std::span<const double> xg = geom.x();
  const fem::CoordinateElement& cmap = geom.cmap();
  const std::size_t nn = xdofs.links(cells[0]).size();
  std::vector<std::array<double, 6>> boxes(cells.size());
  double diam = 0;
  for (std::size_t k = 0; k < cells.size(); ++k)
  {
    auto& b = boxes[k];
    b = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (auto n : xdofs.links(cells[k]))
      for (int j = 0; j < 3; ++j)
      {
        b[j] = std::min(b[j], xg[3 * n + j]);
        b[3 + j] = std::max(b[3 + j], xg[3 * n + j]);
      }
    diam = std::max({diam, b[3] - b[0], b[4] - b[1], b[5] - b[2]});
  }
  const double pad = 1e-3 * diam; // curved (P2) faces: g(X_i) may sit just outside

  // Rows: the nodes of face A (blocked dof indices).
  auto dofmap = V.dofmap();
  if (static_cast<std::size_t>(dofmap->cell_dofs(cells[0]).size()) != nn)
    throw std::logic_error("partner field: geometry and displacement degrees differ");
  auto nodes_a = fem::locate_dofs_topological(V, tdim - 1, faces_a);
  const auto X = V.tabulate_dof_coordinates(false);
  const std::int32_t nlocal = dofmap->index_map->size_local() * 3;

  Mat P;
  MatCreate(comm, &P);
  MatSetSizes(P, nlocal, nlocal, PETSC_DETERMINE, PETSC_DETERMINE);
  MatSetType(P, MATAIJ);
  MatSeqAIJSetPreallocation(P, static_cast<PetscInt>(nn), nullptr);
  MatMPIAIJSetPreallocation(P, static_cast<PetscInt>(nn), nullptr, 0, nullptr);

  std::vector<double> geometry(nn * 3), basis(cmap.tabulate_shape(0, 1)[2]);
  namespace stdex = std::experimental;
  using mdspan2 = stdex::mdspan<double, stdex::dextents<std::size_t, 2>>;
  using cmdspan2 = stdex::mdspan<const double, stdex::dextents<std::size_t, 2>>;
  for (auto i : nodes_a)
  {
    // y = g(X_i) = G X_i + t
    std::array<double, 3> y;
    for (int r = 0; r < 3; ++r)
      y[r] = g[3 * r] * X[3 * i] + g[3 * r + 1] * X[3 * i + 1] + g[3 * r + 2] * X[3 * i + 2] + g[9 + r];
    double best = std::numeric_limits<double>::infinity();
    std::int32_t best_cell = -1;
    std::array<double, 3> best_xi{};
    for (std::size_t k = 0; k < cells.size(); ++k)
    {
      const auto& b = boxes[k];
      if (y[0] < b[0] - pad || y[1] < b[1] - pad || y[2] < b[2] - pad || y[0] > b[3] + pad
          || y[1] > b[4] + pad || y[2] > b[5] + pad)
        continue;
      auto gn = xdofs.links(cells[k]);
      for (std::size_t n = 0; n < nn; ++n)
        for (int j = 0; j < 3; ++j)
          geometry[3 * n + j] = xg[3 * gn[n] + j];
      std::array<double, 3> xi{};
      try
      {
        cmap.pull_back_nonaffine(mdspan2(xi.data(), 1, 3), cmdspan2(y.data(), 1, 3),
                                 cmdspan2(geometry.data(), nn, 3), 1e-12, 20);
      }
      catch (const std::runtime_error&)
      {
        continue; // Newton of the pull-back failed: y is far outside this cell
      }
      if (outside(xi) < best)
      {
        best = outside(xi);
        best_cell = cells[k];
        best_xi = xi;
      }
    }
    if (best > 1e-3)
      throw InputError(fmt::format(
          "energy term '{}': the map g sends the node ({:.6g}, {:.6g}, {:.6g}) m of face A ({}) to "
          "({:.6g}, {:.6g}, {:.6g}) m, which is in no cell touching face B ({}); check the map "
          "keys {} and {}", term, X[3 * i], X[3 * i + 1], X[3 * i + 2], info.face_a, y[0], y[1],
          y[2], info.face_b, key_of(info.map_matrix), key_of(info.map_shift)));
    // Row 3 i + c: u_c(y) = sum_j phi_j(xi) u_c(node j), the element basis at xi
    // (the geometry and u are Lagrange elements of the same degree: local
    // node j is the same point for both).
    cmap.tabulate(0, std::span<const double>(best_xi.data(), 3), {1, 3}, basis);
    auto cd = dofmap->cell_dofs(best_cell);
    for (int c = 0; c < 3; ++c)
    {
      const PetscInt row = 3 * i + c;
      for (std::size_t j = 0; j < nn; ++j)
      {
        const PetscInt col = 3 * cd[j] + c;
        const PetscScalar val = basis[j];
        if (val != 0.0)
          MatSetValues(P, 1, &row, 1, &col, &val, INSERT_VALUES);
      }
    }
  }
  MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY);
  return P;
}

PartnerField::PartnerField(generated::PartnerInfo info, std::shared_ptr<const fem::FunctionSpace> V)
    : _info(std::move(info)), _V(std::move(V)), _w(std::make_shared<fem::Function<T>>(_V))
{
  _w->name = _info.coefficient;
}

PartnerField::~PartnerField()
{
  destroy(_P);
  destroy(_Auw);
  destroy(_Aww);
  if (_bw)
    VecDestroy(&_bw);
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
    destroy(_P);
    _P = build_partner_interpolation(*_V, facets, _info, g);
    _map = g;
  }
  // w = P u
  Vec ux = la::petsc::create_vector_wrap(*u.x());
  Vec wx = la::petsc::create_vector_wrap(*_w->x());
  MatMult(_P, ux, wx);
  VecDestroy(&ux);
  VecDestroy(&wx);
  _w->x()->scatter_fwd();
}

void PartnerField::add_gradient(Vec b, double s)
{
  if (!_bw)
    _bw = la::petsc::create_vector(*_V->dofmap()->index_map, _V->dofmap()->index_map_bs());
  assemble_ghosted(_bw, *_Ew);
  VecScale(_bw, s);
  MatMultTransposeAdd(_P, _bw, b, b); // b = b + P^T (s E_w)
}

Mat PartnerField::hessian_coupling(std::span<const std::int8_t> constrained)
{
  auto assemble = [](Mat& A, const fem::Form<T>& a)
  {
    if (!A)
      A = fem::petsc::create_matrix(a, "aij");
    MatZeroEntries(A);
    fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A, ADD_VALUES), a, {});
    MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  };
  assemble(_Auw, *_Euw);
  assemble(_Aww, *_Eww);
  Mat K, KT, Q;
  MatMatMult(_Auw, _P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &K); // E_uw P
  MatTranspose(K, MAT_INITIAL_MATRIX, &KT);                     // P^T E_wu
  MatPtAP(_Aww, _P, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &Q);     // P^T E_ww P
  MatAXPY(K, 1.0, KT, DIFFERENT_NONZERO_PATTERN);
  MatAXPY(K, 1.0, Q, DIFFERENT_NONZERO_PATTERN);
  MatDestroy(&KT);
  MatDestroy(&Q);
  std::vector<PetscInt> rows;
  for (std::size_t i = 0; i < constrained.size(); ++i)
    if (constrained[i])
      rows.push_back(static_cast<PetscInt>(i));
  MatZeroRowsColumns(K, static_cast<PetscInt>(rows.size()), rows.data(), 0.0, nullptr, nullptr);
  return K;
}
} // namespace breastsim
