// SPDX-License-Identifier: LGPL-3.0-or-later
#include "posture_solve.hpp"
#include "case_options.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "timer.hpp"
#include <fmt/format.h>
#include <fmt/ranges.h>

namespace breastsim
{
namespace
{
PostureResult solve_from(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                         const Posture& posture, const Config& c, const Guess& guess,
                         WarmStartReport& start)
{
  Stopwatch clock("posture solve");
  PostureResult r;
  r.posture = posture;
  const std::string context = fmt::format("posture '{}' (theta = {:g} deg)", posture.name, posture.theta_deg);
  // Each posture starts from the neutral state (or from the guess).
  model.displacement()->x()->set(0.0);
  model.state()->x()->set(0.0); // mixed: the pressure too (else the same field)
  const double g = CaseOptions::from(c).gravity;
  const double f_ext = set_gravity(model, gravity_vector(posture.theta_deg, g));
  start = solve_at_full_load(model, newton, guess, LoadStepOptions::from(c), context, f_ext);
  r.path = std::move(start.path);
  r.converged_from_guess = start.converged;
  r.observables = probe.measure(model);
  r.min_det_F = model.min_detF(); // > 0: no element of the deformed state is inverted
  if (model.mixed())
    r.mean_pressure = model.mean_pressure();
  r.seconds = clock.seconds();
  return r;
}
} // namespace

PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, const Guess& guess)
{
  WarmStartReport start;
  return solve_from(model, newton, probe, posture, c, guess, start);
}

PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, CoarseStart* coarse)
{
  if (!coarse)
    return solve_posture(model, newton, probe, posture, c, Guess{});
  const double g = CaseOptions::from(c).gravity;
  CoarseGuessReport ladder;
  Guess guess;
  guess.name = "the coarse solution";
  guess.set = [&](Model& fine, std::string& reason)
  {
    const bool ok = coarse->solve_and_transfer(fine, gravity_vector(posture.theta_deg, g), ladder);
    reason = ladder.reason;
    return ok;
  };
  WarmStartReport start;
  PostureResult r = solve_from(model, newton, probe, posture, c, guess, start);
  ladder.used = start.used;
  if (!start.used)
    ladder.reason = start.reason;
  r.coarse = std::move(ladder);
  log::debug("posture '{}': coarse start: {} Newton iterations on the levels below ({}), {} fine",
             posture.name, r.coarse.newton_iterations,
             fmt::join(r.coarse.level_newton_iterations, ", "), r.path.newton_iterations);
  return r;
}
} // namespace breastsim
