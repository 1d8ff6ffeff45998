#include "load_stepping.hpp"
#include "errors.hpp"
#include "log.hpp"
#include <algorithm>
#include <cmath>
#include <dolfinx/la/petsc.h>
#include <fmt/format.h>

namespace breastsim
{
namespace
{
/// Secant predictor: u = u_s + a (u_s - u_prev), a = (s_try - s) / (s - s_prev),
/// kept only when it is admissible (det F > 0) and has a lower energy at the
/// new load than u_s; otherwise the model is left at u_s.
void predict(Model& model, const std::vector<T>& u_s, const std::vector<T>& u_prev, double a,
             LoadPathReport& rep)
{
  auto x = model.displacement()->x()->mutable_array();
  std::copy(u_s.begin(), u_s.end(), x.begin());
  const double e_s = model.energy();
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = u_s[i] + a * (u_s[i] - u_prev[i]);
  model.displacement()->x()->scatter_fwd();
  const bool admissible = model.min_detF() > 0;
  const double e_p = admissible ? model.energy() : 0.0;
  if (admissible && std::isfinite(e_p) && e_p < e_s)
  {
    ++rep.predictions;
    log::debug("  predictor accepted: energy {:.9e} -> {:.9e}", e_s, e_p);
    return;
  }
  std::copy(u_s.begin(), u_s.end(), x.begin());
  model.displacement()->x()->scatter_fwd();
  log::debug("  predictor rejected ({})", admissible ? "no energy decrease" : "det F <= 0");
}
} // namespace

LoadPathReport continuation(Model& model, NewtonSolver& newton, const std::string& parameter,
                            double from, double to, const LoadStepOptions& opt,
                            const std::string& context, double reference_norm)
{
  LoadPathReport rep;
  newton.invalidate_preconditioner(); // the state may have changed since the last solve
  auto x = model.displacement()->x()->mutable_array();
  std::vector<T> saved(x.begin(), x.end());
  std::vector<T> previous; // the converged state before `saved` (at s_prev)
  double s = 0, s_prev = 0, ds = std::min(1.0, opt.initial_step);
  while (s < 1.0)
  {
    const double s_try = std::min(1.0, s + ds);
    model.set_parameter(parameter, {from + s_try * (to - from)});
    if (opt.predictor && !previous.empty())
      predict(model, saved, previous, (s_try - s) / (s - s_prev), rep);
    NewtonReport nr = newton.solve(reference_norm);
    rep.newton_iterations += nr.iterations;
    rep.linear_iterations += nr.linear_iterations;
    if (nr.converged)
    {
      ++rep.steps;
      s_prev = s;
      s = s_try;
      previous.swap(saved);
      saved.assign(x.begin(), x.end());
      log::debug("{}: {} = {:.4g} converged in {} Newton iterations", context, parameter,
                 from + s * (to - from), nr.iterations);
      if (nr.iterations <= 6)
        ds *= opt.growth;
    }
    else
    {
      ++rep.failed_steps;
      // Restore the last converged state and cut the step back.
      std::copy(saved.begin(), saved.end(), x.begin());
      model.displacement()->x()->scatter_fwd();
      ds *= 0.5;
      log::debug("{}: step to {} = {:.4g} failed ({}); cutting back to {:.4g}", context,
                 parameter, from + s_try * (to - from), nr.message, ds);
      if (ds < opt.min_step)
      {
        model.set_parameter(parameter, {from + s * (to - from)});
        throw SolveError(fmt::format(
            "{}: no convergence beyond {} = {:.6g} (fraction {:.4g} of the path) even with "
            "the smallest step {:.3g}; last failure: {}",
            context, parameter, from + s_try * (to - from), s_try, opt.min_step, nr.message));
      }
    }
  }
  return rep;
}
} // namespace breastsim
