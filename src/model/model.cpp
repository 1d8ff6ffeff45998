// SPDX-License-Identifier: LGPL-3.0-or-later
#include "model.hpp"
#include "dense_table.hpp"
#include "ghosted_assembly.hpp"
#include "breastsim_registry.hpp"
#include "breastsim_mixed_registry.hpp"
#include "errors.hpp"
#include "petsc.hpp"
#include "composite_form.hpp"
#include <algorithm>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/utils.h>
#include <dolfinx/common/IndexMap.h>
#include <numeric>
#include <fmt/format.h>
#include <limits>

namespace breastsim
{
using namespace dolfinx;

Model::Model(TaggedDolfinxMesh mesh, Constraints constraints, TissueFormulation formulation)
    : _mesh(std::move(mesh)), _constraints(constraints)
{
  auto factory = generated::function_space(_mesh.degree);
  if (!factory)
    throw InputError(fmt::format("element order {} is not compiled in (available: 1, 2)",
                                 _mesh.degree));
  if (formulation == TissueFormulation::mixed)
  {
    _mixed = std::make_shared<MixedState>(_mesh);
    _state_bcs = _mixed->bcs(_mesh, _constraints.symmetry, _constraints.fixed_base);
  }
  _V = _mixed ? _mixed->displacement_space()
              : std::make_shared<fem::FunctionSpace>(fem::create_functionspace(factory, "u", _mesh.mesh));
  _u = std::make_shared<fem::Function<T>>(_V);
  _u->name = "displacement";

  for (const auto& p : generated::parameters())
    _constants[p.name] = std::make_shared<fem::Constant<T>>(std::span<const T>(p.default_value));
  for (const auto& t : generated::terms())
    _constants["on_" + t.name] = std::make_shared<fem::Constant<T>>(t.default_on ? 1.0 : 0.0);

  // Constraints: sliding symmetry (u_x = 0 on x = 0) and the optional fixed base.
  const int tdim = _mesh.mesh->topology().dim();
  if (_constraints.symmetry)
  {
    auto V0 = _V->sub({0});
    auto facets = tagged_facets(*_mesh.facets, generated::tag("symmetry"));
    auto dofs = fem::locate_dofs_topological(*V0, tdim - 1, facets);
    _bcs.push_back(std::make_shared<const fem::DirichletBC<T>>(T(0), std::move(dofs), V0));
  }
  if (_constraints.fixed_base)
  {
    auto facets = tagged_facets(*_mesh.facets, generated::tag("base"));
    auto dofs = fem::locate_dofs_topological(*_V, tdim - 1, facets);
    _bcs.push_back(std::make_shared<const fem::DirichletBC<T>>(
        std::vector<T>{0, 0, 0}, std::move(dofs), _V));
  }

  // Partner fields: their Coefficients must exist before any form is created
  // (their terms have no mixed forms).
  for (const auto& p : generated::partners())
    if (!_mixed)
      _partners.push_back(std::make_shared<PartnerField>(p, _V));
  for (auto& p : _partners)
  {
    const std::string& t = p->info().term;
    p->set_forms(create("partner_residual_" + t, 1), create("partner_jacobian_uw_" + t, 2),
                 create("partner_jacobian_ww_" + t, 2));
  }

  _volume = create("volume", 0);
  forms("");
}

ufcx_form* Model::mixed_form(const std::string& name) const
{
  return _mixed ? generated::mixed_form(name) : nullptr;
}

std::shared_ptr<fem::Form<T>> Model::create(const std::string& name, int rank)
{
  // Mixed: the terms' forms on W (coefficient w); the term-free forms
  // (volume, areas) on the displacement space.
  ufcx_form* mixed = mixed_form(name);
  ufcx_form* f = mixed ? mixed : generated::form(name, _mesh.degree);
  if (!f)
    throw std::logic_error("no compiled form " + name);
  std::map<std::string, std::shared_ptr<const fem::Constant<T>>> constants(_constants.begin(),
                                                                            _constants.end());
  std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces(rank, mixed ? _mixed->W() : _V);
  std::map<std::string, std::shared_ptr<const fem::Function<T>>> coefficients = {{"u", _u}};
  if (mixed)
    coefficients = {{"w", _mixed->w()}};
  for (const auto& p : _partners)
    coefficients[p->info().coefficient] = p->field();
  return std::make_shared<fem::Form<T>>(fem::create_form<T>(
      *f, spaces, coefficients, constants,
      {{fem::IntegralType::exterior_facet, _mesh.facets.get()}}, _mesh.mesh));
}

Model::FormSet& Model::forms(const std::string& term)
{
  auto it = _forms.find(term);
  if (it != _forms.end())
    return it->second;
  if (!term.empty())
  {
    if (!_constants.count("on_" + term))
      throw InputError("unknown energy term '" + term + "'");
    if (_mixed && !mixed_form("energy_" + term))
      throw InputError(fmt::format("energy term '{}' has no mixed form: not available with "
                                   "tissue.formulation = \"mixed\"", term));
    FormSet s{create("energy_" + term, 0), create("residual_" + term, 1),
              create("jacobian_" + term, 2)};
    return _forms.emplace(term, s).first->second;
  }
  // The total Pi = sum_k on_k E_k: the terms' own forms behind their switches.
  std::vector<SwitchedForm> energy, residual, jacobian;
  for (const auto& t : generated::terms())
  {
    if (_mixed && !mixed_form("energy_" + t.name))
      continue; // switched off (set_term refuses it)
    const FormSet& f = forms(t.name);
    auto on = _constants.at("on_" + t.name);
    energy.push_back({f.energy, on});
    residual.push_back({f.residual, on});
    jacobian.push_back({f.jacobian, on});
  }
  const auto* tags = _mesh.facets.get();
  FormSet s{compose_forms(energy, tags), compose_forms(residual, tags), compose_forms(jacobian, tags)};
  return _forms.emplace(term, s).first->second;
}

void Model::set_parameter(const std::string& name, const std::vector<double>& value)
{
  auto it = _constants.find(name);
  if (it == _constants.end() || name.rfind("on_", 0) == 0)
    throw InputError("unknown model parameter '" + name + "'");
  if (it->second->value.size() != value.size())
    throw InputError(fmt::format("parameter '{}' takes {} value(s), got {}", name,
                                 it->second->value.size(), value.size()));
  it->second->value.assign(value.begin(), value.end());
}

std::vector<double> Model::parameter(const std::string& name) const
{
  auto it = _constants.find(name);
  if (it == _constants.end())
    throw InputError("unknown model parameter '" + name + "'");
  return {it->second->value.begin(), it->second->value.end()};
}

std::vector<std::string> Model::parameter_names() const
{
  std::vector<std::string> names;
  for (const auto& p : generated::parameters())
    names.push_back(p.name);
  return names;
}

void Model::set_term(const std::string& term, bool on)
{
  auto it = _constants.find("on_" + term);
  if (it == _constants.end())
    throw InputError("unknown energy term '" + term + "'");
  if (on && _mixed && !mixed_form("energy_" + term))
    throw InputError(fmt::format("key 'tissue.formulation' = \"mixed\" with terms.{} = true: the "
                                 "term has a partner field and no mixed form", term));
  it->second->value = {on ? 1.0 : 0.0};
}

bool Model::term_on(const std::string& term) const
{
  auto it = _constants.find("on_" + term);
  if (it == _constants.end())
    throw InputError("unknown energy term '" + term + "'");
  return it->second->value[0] != 0.0;
}

std::vector<std::string> Model::term_names() const
{
  std::vector<std::string> names;
  for (const auto& t : generated::terms())
    names.push_back(t.name);
  return names;
}

std::vector<std::int32_t> Model::boundary_nodes(const std::string& tag) const
{
  auto facets = tagged_facets(*_mesh.facets, generated::tag(tag));
  auto nodes = fem::locate_dofs_topological(*_V, 2, facets);
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

std::int64_t Model::num_dofs() const
{
  if (_mixed)
    return _mixed->num_dofs();
  return _V->dofmap()->index_map->size_global() * _V->dofmap()->index_map_bs();
}

double Model::partner_weight(const PartnerField& p, const std::string& term) const
{
  if (term.empty())
    return term_on(p.info().term) ? _constants.at("on_" + p.info().term)->value[0] : 0.0;
  return term == p.info().term ? 1.0 : 0.0;
}

AffineMap Model::partner_map(const PartnerField& p) const
{
  const auto G = parameter(p.info().map_matrix), t = parameter(p.info().map_shift);
  AffineMap g;
  std::copy(G.begin(), G.end(), g.begin());
  std::copy(t.begin(), t.end(), g.begin() + 9);
  return g;
}

void Model::update_partners(const std::string& term)
{
  for (auto& p : _partners)
    if (partner_weight(*p, term) != 0.0)
      p->update(*_u, *_mesh.facets, partner_map(*p));
}

const PartnerField& Model::partner(const std::string& term)
{
  for (auto& p : _partners)
    if (p->info().term == term)
    {
      p->update(*_u, *_mesh.facets, partner_map(*p));
      return *p;
    }
  throw InputError("energy term '" + term + "' has no partner field");
}

void Model::pull_state()
{
  if (_mixed)
    _mixed->pull(*_u);
}

double Model::mean_pressure()
{
  if (!_mixed)
    throw std::logic_error("mean_pressure: the model has no pressure (displacement formulation)");
  pull_state();
  double local[2] = {fem::assemble_scalar(*create("pressure_integral", 0)),
                     fem::assemble_scalar(*create("reference_volume", 0))};
  double global[2];
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, _mesh.mesh->comm());
  return global[0] / global[1]; // int p dV / int 1 dV
}

double Model::energy(const std::string& term)
{
  pull_state();
  update_partners(term);
  double local = fem::assemble_scalar(*forms(term).energy), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, _mesh.mesh->comm());
  return global;
}

double Model::volume()
{
  double local = fem::assemble_scalar(*_volume), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, _mesh.mesh->comm());
  return global;
}

double Model::area(const std::string& tag)
{
  auto form = create("area_" + tag, 0);
  double local = fem::assemble_scalar(*form), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, _mesh.mesh->comm());
  return global;
}

double Model::min_detF()
{
  if (!_detF)
    _detF = std::make_shared<fem::Expression<T>>(fem::create_expression<T>(
        *generated::detF_expression(_mesh.degree), {{"u", _u}}, {}, _mesh.mesh));
  const fem::Expression<T>& expr = *_detF;
  const std::int32_t ncells = _mesh.mesh->topology().index_map(3)->size_local();
  std::vector<std::int32_t> cells(ncells);
  std::iota(cells.begin(), cells.end(), 0);
  const std::size_t npts = expr.X().second[0];
  DenseTable values{std::vector<double>(ncells * npts), npts};
  expr.eval(std::span<const std::int32_t>(cells), values);
  double local = values.data.empty() ? std::numeric_limits<double>::infinity()
                                     : *std::min_element(values.data.begin(), values.data.end());
  if (std::isnan(local))
    local = -std::numeric_limits<double>::infinity();
  double global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MIN, _mesh.mesh->comm());
  return global;
}

void Model::set_displacement(Vec x)
{
  auto state = this->state();
  PetscVec ux(la::petsc::create_vector_wrap(*state->x()));
  if (x != ux.get())
    PETSC_CHECK(VecCopy(x, ux.get()));
  state->x()->scatter_fwd();
  if (_mixed)
    _mixed->push(*_u);
}

void Model::assemble_residual(Vec b, const std::string& term)
{
  FormSet& f = forms(term);
  pull_state();
  update_partners(term);
  assemble_ghosted(b, *f.residual);
  // Partner fields: the chain rule through w = P u, b += on_k P^T E_w.
  for (auto& p : _partners)
    if (const double s = partner_weight(*p, term); s != 0.0)
      p->add_gradient(b, s);
  // Constrained rows: b = u - g (zero while u satisfies the constraint).
  set_constrained_entries(b, -1.0);
}

void Model::constrain_increment(Vec du) const { set_constrained_entries(du, 1.0); }

void Model::constrain_displacement()
{
  auto x = _u->x()->mutable_array();
  for (const auto& bc : _bcs)
    bc->set(x, 1.0);
  _u->x()->scatter_fwd();
}

void Model::set_constrained_entries(Vec b, double scale) const
{
  PetscVec ux(la::petsc::create_vector_wrap(*(_mixed ? _mixed->w() : _u)->x()));
  fem::petsc::set_bc(b, state_bcs(), ux.get(), scale); // b = scale (g - u) on constrained dofs
}

double Model::residual_norm(const std::string& term)
{
  PetscVec b(create_vector());
  assemble_residual(b.get(), term);
  PetscReal n;
  PETSC_CHECK(VecNorm(b.get(), NORM_2, &n));
  return n;
}

void Model::assemble_jacobian(Mat A, const std::string& term)
{
  FormSet& f = forms(term);
  pull_state();
  update_partners(term);
  PETSC_CHECK(MatZeroEntries(A));
  // Straight into the CSR values once the pattern of A is known (AIJ; under
  // MPI ghost rows still through PETSc); otherwise (first assembly) through
  // PETSc, and the pattern is recorded.
  const bool fast = _jacobian_adder.matches(A);
  if (fast)
    assemble_recorded(A, *f.jacobian);
  else
    fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A, ADD_VALUES), *f.jacobian, state_bcs());
  // Partner fields: A += on_k (E_uw P + P^T E_wu + P^T E_ww P), constrained
  // rows and columns excluded; added before the first final assembly so that
  // PETSc keeps these entries in the matrix structure.
  for (auto& p : _partners)
    if (const double s = partner_weight(*p, term); s != 0.0)
    {
      PetscMat K(p->hessian_coupling(constrained_markers()));
      add_scaled(A, K.get(), s);
    }
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY));
  fem::set_diagonal<T>(la::petsc::Matrix::set_fn(A, INSERT_VALUES), *(_mixed ? _mixed->W() : _V),
                       state_bcs());
  PETSC_CHECK(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PETSC_CHECK(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  if (!fast)
    _jacobian_adder.record(A);
}

void Model::assemble_recorded(Mat A, const fem::Form<T>& jacobian)
{
  _jacobian_adder.begin(A, &jacobian); // same form: replay the offsets
  try
  {
    fem::assemble_matrix([this](auto rows, auto cols, auto vals)
                         { _jacobian_adder.add(rows, cols, vals); return 0; },
                         jacobian, state_bcs());
  }
  catch (...)
  {
    _jacobian_adder.cancel(A);
    throw;
  }
  _jacobian_adder.end(A);
}

std::vector<std::int8_t> Model::constrained_markers() const
{
  const auto& map = *_V->dofmap()->index_map;
  std::vector<std::int8_t> marker(3 * (map.size_local() + map.num_ghosts()), 0);
  for (const auto& bc : _bcs)
    bc->mark_dofs(marker);
  return marker;
}

Mat Model::create_matrix()
{
  // The pattern of the Jacobian form, plus (partner fields on) the partner
  // couplings E_uw P + P^T E_wu + P^T E_ww P: face A's cells with the cells
  // holding g(X).
  bool partners = false;
  for (auto& p : _partners)
    partners = partners || partner_weight(*p, "") != 0.0;
  if (partners)
    update_partners("");
  la::SparsityPattern pattern = fem::create_sparsity_pattern(*forms("").jacobian);
  pattern.assemble();
  PetscMat A(la::petsc::create_matrix(_mesh.mesh->comm(), pattern, "aij"));
  insert_pattern(A.get(), pattern);
  if (partners)
  {
    // The couplings may join blocks on different ranks, outside the form's
    // pattern: inserted into the assembled matrix.
    for (auto& p : _partners)
      if (partner_weight(*p, "") != 0.0)
      {
        PetscMat K(p->hessian_coupling({}));
        insert_coupling_blocks(A.get(), K.get());
      }
    PETSC_CHECK(MatAssemblyBegin(A.get(), MAT_FINAL_ASSEMBLY));
    PETSC_CHECK(MatAssemblyEnd(A.get(), MAT_FINAL_ASSEMBLY));
  }
  _jacobian_adder.record(A.get()); // the first Jacobian already goes straight into the values
  return A.release();
}

Vec Model::create_vector() const
{
  const auto& space = _mixed ? *_mixed->W() : *_V;
  return la::petsc::create_vector(*space.dofmap()->index_map, space.dofmap()->index_map_bs());
}
} // namespace breastsim
