#include "posture_solve.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include <chrono>
#include <fmt/format.h>
#include <fmt/ranges.h>

namespace breastsim
{
namespace
{
using clock_type = std::chrono::steady_clock;
double since(clock_type::time_point t0)
{
  return std::chrono::duration<double>(clock_type::now() - t0).count();
}
} // namespace

PostureResult solve_posture(Model& model, NewtonSolver& newton, const ObservableProbe& probe,
                            const Posture& posture, const Config& c, CoarseStart* coarse)
{
  const auto t0 = clock_type::now();
  PostureResult r;
  r.posture = posture;
  const std::string context = fmt::format("posture '{}' (theta = {:g} deg)", posture.name, posture.theta_deg);
  // Each posture starts from the neutral state (or from the coarse solution
  // of the same posture).
  model.displacement()->x()->set(0.0);
  const auto g = gravity_vector(posture.theta_deg, c.number("gravity.g"));
  const double f_ext = set_gravity(model, g);
  if (coarse)
  {
    model.set_parameter("load", {1.0});
    r.coarse = coarse->guess(model, g);
    if (r.coarse.used)
    {
      newton.invalidate_preconditioner();
      const NewtonReport nr = newton.solve(f_ext);
      r.path.newton_iterations = nr.iterations;
      r.path.linear_iterations = nr.linear_iterations;
      if (nr.converged)
        r.path.steps = 1;
      else
      {
        ++r.path.failed_steps;
        log::info("{}: Newton from the coarse solution failed ({}); solving from u = 0", context,
                  nr.message);
        model.displacement()->x()->set(0.0);
      }
    }
    else
      log::info("{}: coarse start not used: {}", context, r.coarse.reason);
    log::debug("{}: coarse start: {} Newton iterations on the levels below ({}), {} fine", context,
               r.coarse.newton_iterations, fmt::join(r.coarse.level_newton_iterations, ", "),
               r.path.newton_iterations);
  }
  if (r.path.steps == 0)
  {
    model.set_parameter("load", {0.0});
    const LoadPathReport p = continuation(model, newton, "load", 0.0, 1.0, load_step_options(c), context, f_ext);
    r.path.steps = p.steps;
    r.path.failed_steps += p.failed_steps;
    r.path.newton_iterations += p.newton_iterations;
    r.path.linear_iterations += p.linear_iterations;
  }
  r.observables = probe.measure(model);
  r.min_det_F = model.min_detF(); // > 0: no element of the deformed state is inverted
  r.seconds = since(t0);
  return r;
}

} // namespace breastsim
