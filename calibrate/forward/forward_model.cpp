// SPDX-License-Identifier: LGPL-3.0-or-later
#include "forward_model.hpp"
#include "case_options.hpp"
#include "cap_morph.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "posture_solve.hpp"
#include "surface_export.hpp"
#include "errors.hpp"
#include "schema.hpp"
#include <fmt/format.h>
#include <algorithm>

namespace breastsim::calibration
{
ForwardModel::ForwardModel(std::vector<Posture> postures, MPI_Comm comm, bool morph)
    : _postures(std::move(postures)), _comm(comm), _morph(morph), _last(_postures.size()),
      _solved_at(_postures.size()), _tangent(_postures.size())
{
}

ForwardModel::~ForwardModel() = default;

std::int64_t ForwardModel::dofs() const { return _model ? _model->num_dofs() : 0; }

void ForwardModel::attach_solver(const Config& c)
{
  // The Newton solver (AMG near-nullspace) and the probe (reference node
  // coordinates) depend on the node positions: rebuilt after every change.
  _newton.reset();
  _probe.reset();
  _newton = std::make_unique<NewtonSolver>(*_model, NewtonOptions::from(c));
  // The nipple node (0, H, nipple_z): a morphed cap's apex moves with H.
  _probe = std::make_unique<ObservableProbe>(*_model, std::array<double, 3>{0.0, _H, _nipple_z});
}

void ForwardModel::rebuild(const Config& c)
{
  _newton.reset();
  _probe.reset();
  const CaseOptions o = CaseOptions::from(c);
  _model = std::make_unique<Model>(build_neutral_mesh(c, _comm), Constraints{true, o.fixed_base});
  _R = _R0 = o.geometry.R;
  _H = _H0 = o.geometry.H;
  _nipple_z = o.geometry.nipple_z;
  _mesh_size = o.geometry.mesh_size;
  _fixed_base = o.fixed_base;
  _order = o.geometry.order;
  _refinements = o.geometry.refinements;
  const auto x = _model->mesh().mesh->geometry().x();
  _X0.assign(x.begin(), x.end());
  attach_solver(c);
  for (auto& u : _last)
    u.clear(); // solutions on another mesh cannot start this one
  for (auto& at : _solved_at)
    at = nullptr;
  for (auto& t : _tangent)
    t = {};
  ++_meshes;
}

void ForwardModel::morph(double R, double H)
{
  // Every geometry node (owned and ghost, P2 edge nodes too) is mapped from
  // its generated position, so the result does not depend on the path of R, H.
  auto x = _model->mesh().mesh->geometry().x();
  std::copy(_X0.begin(), _X0.end(), x.begin());
  meshes::morph_cap(x, {_R0, _H0}, {R, H});
  _R = R;
  _H = H;
  ++_morphs;
  // The last solutions stay as warm starts: same topology, nearby shape.
}

Observables ForwardModel::solve_one(std::size_t i, const Config& c)
{
  Model& m = *_model;
  auto x = m.displacement()->x()->mutable_array();
  // Warm start: the equilibrium of the same posture at the previous
  // parameters, solved directly at full load (solve_at_full_load: from rest
  // with the gravity ramp of `simulate` if it is not admissible or fails).
  Guess guess;
  guess.name = "the last solution";
  guess.quiet = true;
  if (!_last[i].empty())
    guess.set = [&, step = predictor_step(i, c)](Model& model, std::string&)
    {
      std::copy(_last[i].begin(), _last[i].end(), x.begin());
      for (std::size_t k = 0; k < step.size(); ++k)
        x[k] += step[k];
      model.displacement()->x()->scatter_fwd();
      return true;
    };
  const PostureResult r = breastsim::solve_posture(m, *_newton, *_probe, _postures[i], c, guess);
  if (r.converged_from_guess)
    ++_warm_starts;
  _last[i].assign(x.begin(), x.end());
  _solved_at[i] = c.to_json();
  return r.observables;
}

std::vector<T> ForwardModel::predictor_step(std::size_t i, const Config& c) const
{
  const Tangent& t = _tangent[i];
  if (t.keys.empty() || _solved_at[i] != t.at.to_json())
    return {};
  Config at = t.at;
  std::vector<double> dp;
  for (const auto& key : t.keys)
  {
    dp.push_back(c.number(key) - at.number(key));
    at.set(key, c.number(key));
  }
  if (at.to_json() != c.to_json())
    return {};
  std::vector<T> step(t.du[0].size(), 0.0);
  for (std::size_t j = 0; j < t.keys.size(); ++j)
    for (std::size_t k = 0; k < step.size(); ++k)
      step[k] += t.du[j][k] * dp[j];
  return step;
}

void ForwardModel::prepare(const Config& c)
{
  const CaseOptions o = CaseOptions::from(c);
  const double R = o.geometry.R, H = o.geometry.H;
  const bool same_mesh = _model && o.geometry.mesh_size == _mesh_size
                         && o.geometry.order == _order && o.geometry.refinements == _refinements
                         && o.fixed_base == _fixed_base;
  if (!same_mesh || (!_morph && (R != _R || H != _H)))
    rebuild(c);
  else if (R != _R || H != _H)
  {
    morph(R, H);
    attach_solver(c);
  }
  apply_parameters(c, *_model);
}

Observables ForwardModel::solve_posture(std::size_t i, const Config& c, const PostureVisitor& visit)
{
  Observables obs = solve_one(i, c);
  ++_posture_solves;
  if (visit)
    visit(i, *_model);
  return obs;
}

std::vector<Observables> ForwardModel::solve(const Config& c)
{
  prepare(c);
  std::vector<Observables> obs;
  for (std::size_t i = 0; i < _postures.size(); ++i)
    obs.push_back(solve_posture(i, c));
  return obs;
}

namespace
{
/// b = -(R(plus) - R(minus)) / width, zero on the constrained rows; the
/// model's parameters are those of `c` again afterwards.
void minus_residual_difference(Model& m, const ForwardModel::CaseDifference& d, const Config& c,
                               Vec b, Vec r_minus, const std::vector<std::int8_t>& fixed)
{
  apply_parameters(d.plus, m);
  m.assemble_residual(b);
  apply_parameters(d.minus, m);
  m.assemble_residual(r_minus);
  apply_parameters(c, m);
  PETSC_CHECK(VecAXPY(b, -1.0, r_minus));
  PETSC_CHECK(VecScale(b, -1.0 / d.width));
  PetscInt owned;
  PETSC_CHECK(VecGetLocalSize(b, &owned));
  PetscScalar* bv;
  PETSC_CHECK(VecGetArray(b, &bv));
  for (PetscInt k = 0; k < owned; ++k)
    if (fixed[k])
      bv[k] = 0; // du/dy = 0 where u is prescribed
  PETSC_CHECK(VecRestoreArray(b, &bv));
}
} // namespace

bool ForwardModel::same_mesh(const Config& a, const Config& b)
{
  const CaseOptions x = CaseOptions::from(a), y = CaseOptions::from(b);
  return x.geometry.R == y.geometry.R && x.geometry.H == y.geometry.H
         && x.geometry.mesh_size == y.geometry.mesh_size && x.geometry.order == y.geometry.order
         && x.geometry.refinements == y.geometry.refinements && x.fixed_base == y.fixed_base
         && x.formulation == y.formulation;
}

void ForwardModel::restore_equilibrium(std::size_t i, const Config& c)
{
  prepare(c);
  if (_last[i].empty() || _solved_at[i] != c.to_json())
    solve_posture(i, c);
  Model& m = *_model;
  if (m.mixed())
    throw std::logic_error("sensitivities: the mixed formulation is not supported");
  auto x = m.displacement()->x()->mutable_array();
  std::copy(_last[i].begin(), _last[i].end(), x.begin());
  m.displacement()->x()->scatter_fwd();
  set_gravity(m, gravity_vector(_postures[i].theta_deg, CaseOptions::from(c).gravity));
  m.set_parameter("load", {1.0});
}

void ForwardModel::sensitivities(std::size_t i, const Config& c,
                                 const std::vector<CaseDifference>& directions,
                                 const SensitivityVisitor& visit)
{
  for (const auto& d : directions)
    if (!same_mesh(c, d.plus) || !same_mesh(c, d.minus) || !(d.width > 0))
      throw std::logic_error("sensitivities: a direction changes the mesh");
  restore_equilibrium(i, c);
  Model& m = *_model;
  // K at the converged state (identity rows and columns on the constrained
  // dofs), factorised once for all directions.
  _newton->assemble_tangent();
  PetscVec r_minus(m.create_vector()), b(m.create_vector()), du(m.create_vector());
  const std::vector<std::int8_t> fixed = m.constrained_markers();
  for (std::size_t j = 0; j < directions.size(); ++j)
  {
    minus_residual_difference(m, directions[j], c, b.get(), r_minus.get(), fixed);
    std::string msg;
    if (!_newton->tangent_solve(b.get(), du.get(), msg))
      throw SolveError(fmt::format("posture '{}': the sensitivity solve of direction {}: {}",
                                   _postures[i].name, j + 1, msg));
    PETSC_CHECK(VecGhostUpdateBegin(du.get(), INSERT_VALUES, SCATTER_FORWARD));
    PETSC_CHECK(VecGhostUpdateEnd(du.get(), INSERT_VALUES, SCATTER_FORWARD));
    Vec local;
    PETSC_CHECK(VecGhostGetLocalForm(du.get(), &local));
    PetscInt n;
    const PetscScalar* a;
    PETSC_CHECK(VecGetLocalSize(local, &n));
    PETSC_CHECK(VecGetArrayRead(local, &a));
    const std::span<const double> dv(a, static_cast<std::size_t>(n));
    visit(j, m, dv, _probe->derivative(m, dv));
    PETSC_CHECK(VecRestoreArrayRead(local, &a));
    PETSC_CHECK(VecGhostRestoreLocalForm(du.get(), &local));
  }
}

std::optional<ForwardModel::CaseDifference> ForwardModel::key_difference(const Config& c,
                                                                         const std::string& key)
{
  constexpr double e = 1e-4; // relative step
  const KeyInfo& info = key_info(key);
  if (info.ufl_name.empty() || info.type != KeyType::number)
    return std::nullopt;
  const double p = c.number(key), h = e * (p != 0 ? std::abs(p) : 1.0);
  CaseDifference d{c, c, 2 * h};
  d.plus.set(key, p + h);
  d.minus.set(key, p - h);
  if (!same_mesh(c, d.plus) || !same_mesh(c, d.minus))
    return std::nullopt;
  return d;
}

std::vector<Observables> ForwardModel::sensitivities(std::size_t i, const Config& c,
                                                     const std::vector<std::string>& keys)
{
  std::vector<CaseDifference> directions;
  for (const auto& k : keys)
  {
    auto d = key_difference(c, k);
    if (!d)
      throw std::logic_error(fmt::format("sensitivities: '{}' is not a material parameter", k));
    directions.push_back(std::move(*d));
  }
  std::vector<Observables> out(keys.size());
  Tangent tangent{c, keys, std::vector<std::vector<T>>(keys.size())};
  sensitivities(i, c, directions,
                [&](std::size_t j, const Model&, std::span<const double> du, const Observables& d)
                {
                  out[j] = d;
                  tangent.du[j].assign(du.begin(), du.end());
                });
  _tangent[i] = std::move(tangent);
  return out;
}

std::vector<nlohmann::json> ForwardModel::surfaces(const Config& c)
{
  prepare(c);
  for (std::size_t i = 0; i < _postures.size(); ++i)
    if (_last[i].empty() || _solved_at[i] != c.to_json())
      solve_posture(i, c);
  std::vector<nlohmann::json> docs;
  auto u = _model->displacement()->x()->mutable_array();
  for (std::size_t i = 0; i < _postures.size(); ++i)
  {
    std::copy(_last[i].begin(), _last[i].end(), u.begin());
    _model->displacement()->x()->scatter_fwd();
    docs.push_back(surface_json(gather_skin_surface(*_model), _postures[i].name,
                                _postures[i].theta_deg));
  }
  return docs;
}
} // namespace breastsim::calibration
