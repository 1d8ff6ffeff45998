// SPDX-License-Identifier: LGPL-3.0-or-later
#include "load_stepping.hpp"
#include "errors.hpp"
#include "log.hpp"
#include <algorithm>
#include <fmt/format.h>

namespace breastsim
{
void LoadPathReport::add(double value, NewtonReport r)
{
  newton_iterations += r.iterations;
  linear_iterations += r.linear_iterations;
  if (r.converged)
    ++steps;
  else
    ++failed_steps;
  solves.push_back({value, std::move(r)});
}

void LoadPathReport::append(LoadPathReport later)
{
  steps += later.steps;
  failed_steps += later.failed_steps;
  newton_iterations += later.newton_iterations;
  linear_iterations += later.linear_iterations;
  for (auto& s : later.solves)
    solves.push_back(std::move(s));
}

LoadPathReport continuation(Model& model, NewtonSolver& newton, const std::string& parameter,
                            double from, double to, const LoadStepOptions& opt,
                            const std::string& context, double reference_norm)
{
  return continuation(model, newton, std::vector<ParameterPath>{{parameter, from, to}}, opt, context,
                      reference_norm);
}

LoadPathReport continuation(Model& model, NewtonSolver& newton, const std::vector<ParameterPath>& parameters,
                            const LoadStepOptions& opt, const std::string& context, double reference_norm)
{
  // Each parameter at fraction s of its path; the first one's value is recorded.
  auto set_all = [&](double s)
  {
    for (const auto& p : parameters)
      model.set_parameter(p.name, {p.from + s * (p.to - p.from)});
  };
  const std::string& parameter = parameters.front().name;
  const double from = parameters.front().from, to = parameters.front().to;
  LoadPathReport rep;
  newton.invalidate_preconditioner(); // the state may have changed since the last solve
  auto x = model.displacement()->x()->mutable_array();
  std::vector<T> saved(x.begin(), x.end());
  double s = 0, ds = std::min(1.0, opt.initial_step);
  while (s < 1.0)
  {
    const double s_try = std::min(1.0, s + ds);
    const double value = from + s_try * (to - from);
    set_all(s_try);
    rep.add(value, newton.solve(reference_norm));
    const NewtonReport& nr = rep.solves.back().newton;
    if (nr.converged)
    {
      s = s_try;
      saved.assign(x.begin(), x.end());
      log::debug("{}: {} = {:.4g} converged in {} Newton iterations", context, parameter,
                 from + s * (to - from), nr.iterations);
      if (nr.iterations <= 6)
        ds *= opt.growth;
    }
    else
    {
      // Restore the last converged state and cut the step back.
      std::copy(saved.begin(), saved.end(), x.begin());
      model.displacement()->x()->scatter_fwd();
      ds *= 0.5;
      log::debug("{}: step to {} = {:.4g} failed ({}); cutting back to {:.4g}", context,
                 parameter, value, nr.message, ds);
      if (ds < opt.min_step)
      {
        set_all(s);
        throw SolveError(fmt::format(
            "{}: no convergence beyond {} = {:.6g} (fraction {:.4g} of the path) even with "
            "the smallest step {:.3g}; last failure: {}",
            context, parameter, value, s_try, opt.min_step, nr.message));
      }
    }
  }
  return rep;
}
} // namespace breastsim
