// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The sum of several forms of one rank as a single dolfinx Form. Each term k
// is its own compiled form (forms/term_forms.py) with a runtime switch on_k;
// for every integral (type, subdomain id) the composite kernel adds the
// element tensors of the terms that have that integral and are on:
//   A_e = sum_k [on_k != 0] A_e^k
// (ffcx kernels accumulate into A_e). Each term's kernel receives its own
// coefficients and constants, gathered from the composite's packed arrays
// (the union of the terms' coefficients and constants, matched by object).
// One assembly pass over the mesh, one sparsity pattern: the composite is
// assembled exactly like a single compiled form of the total energy.
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <petscsystypes.h>
#include <vector>

namespace breastsim
{
struct SwitchedForm
{
  std::shared_ptr<const dolfinx::fem::Form<PetscScalar>> form;
  /// The term's switch: its value[0] != 0 means on (read at every call).
  std::shared_ptr<const dolfinx::fem::Constant<PetscScalar>> on;
};

/// The composite of `terms` (all of the same rank, spaces and mesh).
/// `facet_tags` are the exterior-facet subdomains. Throws std::logic_error
/// on an empty list, mismatched ranks or spaces, or a cell integral over a
/// subdomain (the model has no cell tags).
std::shared_ptr<dolfinx::fem::Form<PetscScalar>>
compose_forms(const std::vector<SwitchedForm>& terms,
              const dolfinx::mesh::MeshTags<std::int32_t>* facet_tags);
} // namespace breastsim
