// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The breast model: displacement space, the composed UFL energy with its
// runtime Constants (bound by name from the generated registry), the
// constraints, and assembly of energy, residual and Jacobian. Nothing here
// names a specific material: parameters and terms come from forms/.
#include "mesh_from_gmsh.hpp"
#include "block_csr_adder.hpp"
#include "partner_field.hpp"
#include "mixed_state.hpp"
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/la/SparsityPattern.h>
#include <map>
#include <memory>
#include <petscmat.h>
#include <petscvec.h>
#include <string>
#include <vector>

namespace breastsim
{
/// Kinematic constraints of the model.
struct Constraints
{
  bool symmetry = true;    ///< u_x = 0 on the symmetry face (sliding)
  bool fixed_base = false; ///< u = 0 on the base (the c -> infinity limit)
};

class Model
{
public:
  /// formulation mixed: the Taylor-Hood (u, p) state (src/model/mixed_state.hpp;
  /// element degree 2), every term from its mixed forms.
  Model(TaggedDolfinxMesh mesh, Constraints constraints = {},
        TissueFormulation formulation = TissueFormulation::displacement);

  // -- Parameters and terms (runtime; never recompiles) --
  /// Set UFL Constant `name` (see forms/*.py). Throws on unknown name/size.
  void set_parameter(const std::string& name, const std::vector<double>& value);
  std::vector<double> parameter(const std::string& name) const;
  /// Names of all runtime parameters (UFL Constants except switches).
  std::vector<std::string> parameter_names() const;
  /// Switch a registered energy term on or off (mixed: InputError naming
  /// tissue.formulation for a term without mixed forms switched on).
  void set_term(const std::string& term, bool on);
  bool term_on(const std::string& term) const;
  std::vector<std::string> term_names() const;

  // -- Mesh and fields --
  const TaggedDolfinxMesh& mesh() const { return _mesh; }
  std::shared_ptr<const dolfinx::fem::FunctionSpace> space() const { return _V; }
  std::shared_ptr<dolfinx::fem::Function<T>> displacement() { return _u; }
  std::shared_ptr<const dolfinx::fem::Function<T>> displacement() const { return _u; }
  /// The Newton unknown: the displacement, or (mixed) w = (u, p); vectors of
  /// create_vector(), set_displacement() and the Jacobian have its layout.
  /// A change of displacement() reaches w's u part at the next assembly.
  std::shared_ptr<dolfinx::fem::Function<T>> state() { return _mixed ? _mixed->w() : _u; }
  bool mixed() const { return _mixed != nullptr; }
  /// Mean pressure int p dV / V over the reference body [Pa] (mixed only).
  double mean_pressure();
  const std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>>& bcs() const
  {
    return _bcs;
  }
  const Constraints& constraints() const { return _constraints; }
  /// Local nodes (blocked dof indices, owned and ghost) on a tagged boundary
  /// part, sorted.
  std::vector<std::int32_t> boundary_nodes(const std::string& tag) const;
  /// Global number of unknowns of the state (displacement, or u and p).
  std::int64_t num_dofs() const;

  // -- Assembly (collective) --
  /// Total energy, or the energy of one term (its switch ignored) if `term`
  /// is non-empty.
  double energy(const std::string& term = "");
  /// Deformed volume of the model (the half breast).
  double volume();
  /// Reference area of a tagged boundary part (base, skin, symmetry, ...).
  double area(const std::string& tag);
  /// Smallest det F over the inversion check points (forms/geometry_forms.py:
  /// P1 vertices, P2 the volume quadrature points; and the centroids) (<= 0: inverted).
  double min_detF();
  /// Residual b = dPi/du with constrained rows set to u - g (ghosts updated).
  void assemble_residual(Vec b, const std::string& term = "");
  /// Constrained entries of a Newton increment set exactly to g - u: an
  /// iterative solve satisfies the identity rows only to its tolerance, and
  /// a drift there would change the energy through the reaction forces
  /// while the residual (zero in those rows) cannot see it.
  void constrain_increment(Vec du) const;
  /// u = g on the constrained dofs (ghosts updated).
  void constrain_displacement();
  /// 1 for every dof (unblocked, local and ghost) fixed by a Dirichlet condition.
  std::vector<std::int8_t> constrained_markers() const;
  /// Euclidean norm of the residual (total, or of one term).
  double residual_norm(const std::string& term = "");
  /// Tangent matrix with constrained rows/columns replaced by the identity.
  void assemble_jacobian(Mat A, const std::string& term = "");
  /// Whether the last assemble_jacobian() added every element matrix through
  /// offsets replayed from the previous assembly (src/model/block_csr_adder.hpp).
  bool last_jacobian_replayed() const { return _jacobian_adder.replayed(); }
  /// A matrix with the sparsity of the Jacobian (AIJ, block size 3), its
  /// pattern inserted (zeros) and recorded for fast assembly. Caller owns.
  Mat create_matrix();
  /// A ghosted vector of the state's layout. Caller owns.
  Vec create_vector() const;
  /// Copy a PETSc vector of the state's layout into the state and u (ghosts updated).
  void set_displacement(Vec x);

  // -- Partner fields (src/model/partner_field.hpp) --
  /// The partner field of a term that declares one (forms/model.py PARTNERS),
  /// brought up to date (P built if needed, w = P u). Throws if `term` has none.
  const PartnerField& partner(const std::string& term);

private:
  struct FormSet
  {
    std::shared_ptr<dolfinx::fem::Form<T>> energy, residual, jacobian;
  };
  FormSet& forms(const std::string& term);
  /// Weight of the partner's term in the total (term "") or in `term`: its
  /// switch, 1 for the term itself, 0 otherwise.
  double partner_weight(const PartnerField& p, const std::string& term) const;
  /// Bring the partners that `term` needs up to date (w = P u).
  void update_partners(const std::string& term);
  AffineMap partner_map(const PartnerField& p) const;
  std::shared_ptr<dolfinx::fem::Form<T>> create(const std::string& name, int rank);
  /// Jacobian assembly straight into A's CSR values (its pattern recorded).
  void assemble_recorded(Mat A, const dolfinx::fem::Form<T>& jacobian);
  /// A += s K (owned rows of K), new nonzeros allocated.
  void add_scaled(Mat A, Mat K, double s) const;
  /// Zero 3x3 blocks of A at the blocks of K's nonzeros (owned rows, global
  /// indices, any rank's columns), allocated; A needs a final assembly after.
  static void insert_coupling_blocks(Mat A, Mat K);
  /// Zeros at every entry of `pattern` (blocked) and the final assembly.
  void insert_pattern(Mat A, const dolfinx::la::SparsityPattern& pattern) const;
  /// b = scale (g - u) on the constrained dofs.
  void set_constrained_entries(Vec b, double scale) const;
  /// The constraints on the state (mixed: on W; else _bcs).
  const std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>>& state_bcs() const
  {
    return _mixed ? _state_bcs : _bcs;
  }
  /// Mixed: w's displacement part = u (before an assembly).
  void pull_state();
  /// Mixed: the compiled form of `name` on W, or nullptr (a displacement form).
  ufcx_form* mixed_form(const std::string& name) const;

  TaggedDolfinxMesh _mesh;
  Constraints _constraints;
  std::shared_ptr<dolfinx::fem::FunctionSpace> _V;
  std::shared_ptr<dolfinx::fem::Function<T>> _u;
  std::map<std::string, std::shared_ptr<dolfinx::fem::Constant<T>>> _constants;
  std::map<std::string, FormSet> _forms; // "" = total
  std::shared_ptr<dolfinx::fem::Form<T>> _volume;
  std::shared_ptr<dolfinx::fem::Expression<T>> _detF; // det F at the check points
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>> _bcs;
  std::vector<std::shared_ptr<PartnerField>> _partners;
  std::shared_ptr<MixedState> _mixed; ///< nullptr: displacement formulation
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<T>>> _state_bcs; ///< mixed: on W
  BlockCsrAdder _jacobian_adder{3}; ///< fast insertion once a matrix's pattern is known
};
} // namespace breastsim
