#include "forward_model.hpp"
#include "log.hpp"
#include "simulate.hpp"
#include <algorithm>

namespace breastsim::calibration
{
ForwardModel::ForwardModel(std::vector<Posture> postures, MPI_Comm comm)
    : _postures(std::move(postures)), _comm(comm), _last(_postures.size())
{
}

ForwardModel::~ForwardModel() = default;

std::int64_t ForwardModel::dofs() const { return _model ? _model->num_dofs() : 0; }

void ForwardModel::rebuild(const Config& c)
{
  _newton.reset();
  _probe.reset();
  _model = std::make_unique<Model>(build_neutral_mesh(c, _comm),
                                   Constraints{true, c.flag("base.fixed")});
  _newton = std::make_unique<NewtonSolver>(*_model, newton_options(c));
  _probe = std::make_unique<ObservableProbe>(*_model,
                                             std::array<double, 3>{0.0, c.number("geometry.H"), 0.0});
  _R = c.number("geometry.R");
  _H = c.number("geometry.H");
  _mesh_size = c.number("geometry.mesh_size");
  _fixed_base = c.flag("base.fixed");
  for (auto& u : _last)
    u.clear(); // solutions on another mesh cannot start this one
  ++_meshes;
}

Observables ForwardModel::solve_one(std::size_t i, const Config& c)
{
  Model& m = *_model;
  auto x = m.displacement()->x()->mutable_array();
  if (!_last[i].empty())
  {
    // Warm start: the equilibrium of the same posture at the previous
    // parameters, solved directly at full load.
    const auto g = gravity_vector(_postures[i].theta_deg, c.number("gravity.g"));
    m.set_parameter("g_vec", {g[0], g[1], g[2]});
    m.set_parameter("load", {1.0});
    const double f_ext = m.residual_norm("gravity");
    std::copy(_last[i].begin(), _last[i].end(), x.begin());
    m.displacement()->x()->scatter_fwd();
    _newton->invalidate_preconditioner();
    const NewtonReport r = _newton->solve(f_ext);
    if (r.converged)
    {
      ++_warm_starts;
      _last[i].assign(x.begin(), x.end());
      return _probe->measure(m);
    }
    log::debug("warm start of posture '{}' failed ({}); solving from rest", _postures[i].name,
               r.message);
  }
  // From rest with the gravity ramp of `simulate`.
  PostureResult r = solve_posture(m, *_newton, *_probe, _postures[i], c);
  _last[i].assign(x.begin(), x.end());
  return r.observables;
}

std::vector<Observables> ForwardModel::solve(const Config& c, const PostureVisitor& visit)
{
  if (!_model || c.number("geometry.R") != _R || c.number("geometry.H") != _H
      || c.number("geometry.mesh_size") != _mesh_size || c.flag("base.fixed") != _fixed_base)
    rebuild(c);
  apply_parameters(c, *_model);
  std::vector<Observables> obs;
  for (std::size_t i = 0; i < _postures.size(); ++i)
  {
    obs.push_back(solve_one(i, c));
    ++_posture_solves;
    if (visit)
      visit(i, *_model);
  }
  return obs;
}
} // namespace breastsim::calibration
