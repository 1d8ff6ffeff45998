// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Partner fields (forms/model.py, forms/tissue_suture.py): a term's energy may
// use, besides u, a Coefficient w = P u holding the values of u at the images
//   g(X_i) = G X_i + t
// of the nodes X_i of its face A (row 3 i + k of P evaluates component k of u
// at g(X_i) with the element basis of the cell, touching face B, that
// contains g(X_i)). UFL gives the partial derivatives in u and w; the chain
// rule through w = P u is applied here:
//   dE/du = E_u + P^T E_w,   d2E/du2 = E_uu + E_uw P + P^T E_wu + P^T E_ww P
// (E_wu = E_uw^T: E is a scalar energy).
// P is the material correspondence: built from g and the reference geometry
// at its first use and kept when the reference is reset (the same material
// points keep the same reference-cell coordinates); rebuilt only when G or t
// change. Under MPI, the cells touching face B (few) are gathered on every
// rank with the global indices of their nodes; each rank builds its owned
// rows of P (global columns), and the products are PETSc's parallel ones.
#include "breastsim_registry.hpp"
#include "petsc.hpp"
#include <array>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <petscmat.h>
#include <span>
#include <vector>

namespace breastsim
{
using T = PetscScalar;

/// The affine map g(X) = G X + t: G row-major (9 values) then t (3 values).
using AffineMap = std::array<double, 12>;

/// Interpolation matrix P (n x n, n = number of displacement unknowns) of
/// the partner `info`: rows of the nodes of face_a, evaluating u at g(X_i)
/// inside the cells touching face_b. Caller owns. Throws InputError naming
/// the term if a face is empty or a mapped node lies in no such cell (more
/// than 1e-3 outside in reference coordinates; then the nearest cell's
/// polynomial is extended up to 0.5 outside it, beyond that an InputError).
/// Collective.
/// How many images g(X_i) lay outside every cell touching face B (taken
/// from the nearest cell's extended polynomial) and how far at most
/// (outside() in that cell's reference coordinates; 0: none), over all ranks.
struct PartnerImageStats
{
  std::int64_t extended = 0;
  double max_outside = 0;
};

Mat build_partner_interpolation(const dolfinx::fem::FunctionSpace& V,
                                const dolfinx::mesh::MeshTags<std::int32_t>& facets,
                                const generated::PartnerInfo& info, const AffineMap& g,
                                PartnerImageStats* stats = nullptr);

class PartnerField
{
public:
  PartnerField(generated::PartnerInfo info, std::shared_ptr<const dolfinx::fem::FunctionSpace> V);
  PartnerField(const PartnerField&) = delete;
  PartnerField& operator=(const PartnerField&) = delete;

  const generated::PartnerInfo& info() const { return _info; }
  /// The Coefficient w (bound by name into every form).
  std::shared_ptr<dolfinx::fem::Function<T>> field() const { return _w; }
  /// The term's partial derivatives E_w, E_uw, E_ww (forms partner_*_<term>).
  void set_forms(std::shared_ptr<dolfinx::fem::Form<T>> Ew, std::shared_ptr<dolfinx::fem::Form<T>> Euw,
                 std::shared_ptr<dolfinx::fem::Form<T>> Eww);
  /// (Re)build P if it does not exist or the map changed, then set w = P u.
  void update(const dolfinx::fem::Function<T>& u,
              const dolfinx::mesh::MeshTags<std::int32_t>& facets, const AffineMap& g);
  /// b += s P^T E_w (owned entries).
  void add_gradient(Vec b, double s);
  /// K = E_uw P + P^T E_wu + P^T E_ww P with the rows and columns of the
  /// dofs marked in `constrained` zeroed. Caller owns.
  Mat hessian_coupling(std::span<const std::int8_t> constrained);
  /// P (nullptr before the first update). Owned by this object.
  Mat interpolation() const { return _P.get(); }
  /// The images of face A's nodes beyond face B's cells, as P was built.
  const PartnerImageStats& image_stats() const { return _stats; }

private:
  generated::PartnerInfo _info;
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _V;
  std::shared_ptr<dolfinx::fem::Function<T>> _w;
  std::shared_ptr<dolfinx::fem::Form<T>> _Ew, _Euw, _Eww;
  PetscMat _P, _Auw, _Aww; ///< P, E_uw, E_ww
  PetscVec _bw;            ///< E_w
  AffineMap _map{};
  PartnerImageStats _stats;
};
} // namespace breastsim
