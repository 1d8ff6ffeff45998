// SPDX-License-Identifier: LGPL-3.0-or-later
#include "warm_start.hpp"
#include "log.hpp"
#include <fmt/format.h>

namespace breastsim
{
namespace
{
template <typename... Args>
void log_fallback(bool quiet, fmt::format_string<Args...> f, Args&&... args)
{
  if (quiet)
    log::debug(f, std::forward<Args>(args)...);
  else
    log::info(f, std::forward<Args>(args)...);
}

/// Set the guess and check it; false (reason in `rep`) if it is not used.
bool start_from_guess(Model& model, const Guess& guess, WarmStartReport& rep)
{
  const double energy_at_rest = model.energy();
  if (!guess.set(model, rep.reason))
    return false;
  rep.reason = inadmissible_guess(model, energy_at_rest);
  return rep.reason.empty();
}
} // namespace

std::string inadmissible_guess(Model& model, double energy_at_rest)
{
  const double detF = model.min_detF();
  if (!(detF > 0))
    return fmt::format("it inverts an element (min det F = {:.3g})", detF);
  const double e = model.energy();
  if (!(e < energy_at_rest))
    return fmt::format("it does not lower the energy ({:.6g} J vs {:.6g} J at u = 0)", e,
                       energy_at_rest);
  return {};
}

WarmStartReport solve_at_full_load(Model& model, NewtonSolver& newton, const Guess& guess,
                                   const LoadStepOptions& ramp, const std::string& context,
                                   double reference_norm)
{
  WarmStartReport rep;
  auto& x = *model.displacement()->x();
  if (guess.set)
  {
    model.set_parameter("load", {1.0});
    x.set(0.0);
    rep.used = start_from_guess(model, guess, rep);
    if (rep.used)
    {
      newton.invalidate_preconditioner();
      NewtonReport nr = newton.solve(reference_norm);
      rep.converged = nr.converged;
      rep.path.add(1.0, std::move(nr));
      if (rep.converged)
        return rep;
      rep.reason = fmt::format("Newton from {} failed ({})", guess.name,
                               rep.path.solves.back().newton.message);
      log_fallback(guess.quiet, "{}: {}; solving from u = 0", context, rep.reason);
    }
    else
      log_fallback(guess.quiet, "{}: {} not used ({}); solving from u = 0", context, guess.name,
                   rep.reason);
  }
  x.set(0.0);
  model.set_parameter("load", {0.0});
  rep.path.append(continuation(model, newton, "load", 0.0, 1.0, ramp, context, reference_norm));
  return rep;
}
} // namespace breastsim
