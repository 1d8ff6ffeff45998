// SPDX-License-Identifier: LGPL-3.0-or-later
#include "optimizer.hpp"
#include "errors.hpp"
#include "least_squares.hpp"
#include <cmath>
#include <exception>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <nlopt.hpp>

namespace breastsim::calibration
{
namespace
{
const std::map<std::string, nlopt::algorithm>& algorithms()
{
  static const std::map<std::string, nlopt::algorithm> a
      = {{"bobyqa", nlopt::LN_BOBYQA}, {"sbplx", nlopt::LN_SBPLX},
         {"neldermead", nlopt::LN_NELDERMEAD}, {"lbfgs", nlopt::LD_LBFGS},
         {"slsqp", nlopt::LD_SLSQP}, {"mma", nlopt::LD_MMA}};
  return a;
}

std::string result_text(nlopt::result r)
{
  switch (r)
  {
  case nlopt::SUCCESS: return "success";
  case nlopt::STOPVAL_REACHED: return "stopval reached";
  case nlopt::FTOL_REACHED: return "converged (relative change of the misfit below ftol)";
  case nlopt::XTOL_REACHED: return "converged (parameter change below xtol)";
  case nlopt::MAXEVAL_REACHED: return "evaluation budget (--max-evals) used up";
  case nlopt::MAXTIME_REACHED: return "time limit reached";
  default: return fmt::format("nlopt result {}", static_cast<int>(r));
  }
}

struct Context
{
  Objective* f;
  const OptimizerOptions* o;
  std::exception_ptr error;
};

double nlopt_objective(const std::vector<double>& y, std::vector<double>& grad, void* data)
{
  auto* ctx = static_cast<Context*>(data);
  try
  {
    if (!grad.empty())
      grad = ctx->f->gradient(y, ctx->o->fd_step);
    return ctx->f->chi2(y);
  }
  catch (...)
  {
    // NLopt would swallow the message: keep the exception and stop.
    ctx->error = std::current_exception();
    throw nlopt::forced_stop();
  }
}
} // namespace

std::vector<std::string> algorithm_names()
{
  std::vector<std::string> n;
  for (const auto& [k, _] : algorithms())
    n.push_back(k);
  n.push_back("lm");
  return n;
}

void check_algorithm(const std::string& name)
{
  if (name != "lm" && !algorithms().count(name))
    throw InputError(fmt::format("--algorithm '{}' is unknown (allowed: {})", name,
                                 fmt::join(algorithm_names(), ", ")));
}

bool uses_gradient(const std::string& name)
{
  check_algorithm(name);
  return name == "lbfgs" || name == "slsqp" || name == "mma" || name == "lm";
}

namespace
{
/// Levenberg-Marquardt (least_squares.hpp) on the weighted residuals with
/// Objective::jacobian (exact for the material parameters).
OptimizerResult minimise_lm(Objective& f, const std::vector<double>& y0, const OptimizerOptions& o)
{
  std::vector<double> lo, hi;
  for (const auto& p : f.fit())
  {
    lo.push_back(std::log(p.lower));
    hi.push_back(std::log(p.upper));
  }
  LsqOptions lsq;
  lsq.max_iterations = std::max(1, o.max_evals);
  lsq.max_evaluations = std::max(1, o.max_evals);
  lsq.xtol = o.xtol_log;
  lsq.ftol_rel = o.ftol_rel;
  lsq.fd_step = o.fd_step;
  lsq.chi2_tol = 1e-4; // the Gauss-Newton model predicts at most this further decrease
  auto r = [&](const std::vector<double>& y) { return f.residuals(y); };
  auto J = [&](const std::vector<double>& y, const std::vector<double>&, int&)
  { return f.jacobian(y, o.fd_step); };
  const LsqResult res = levenberg_marquardt(r, y0, lo, hi, lsq, {}, J);
  return {f.best_y(), f.best_chi2(), "Levenberg-Marquardt: " + res.stop_reason};
}
} // namespace

OptimizerResult minimise(Objective& f, const std::vector<double>& y0, const OptimizerOptions& o)
{
  check_algorithm(o.algorithm);
  if (o.algorithm == "lm")
    return minimise_lm(f, y0, o);
  const auto& fit = f.fit();
  const unsigned n = static_cast<unsigned>(fit.size());
  nlopt::opt opt(algorithms().at(o.algorithm), n);
  std::vector<double> lo, hi;
  for (const auto& p : fit)
  {
    lo.push_back(std::log(p.lower));
    hi.push_back(std::log(p.upper));
  }
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_xtol_abs(o.xtol_log);
  opt.set_ftol_rel(o.ftol_rel);
  opt.set_maxeval(std::max(1, o.max_evals));
  if (!uses_gradient(o.algorithm))
  {
    // Keep the first simplex/trust region inside the bounds.
    std::vector<double> step;
    for (unsigned j = 0; j < n; ++j)
      step.push_back(std::min(o.initial_step, 0.45 * (hi[j] - lo[j])));
    opt.set_initial_step(step);
  }
  Context ctx{&f, &o, nullptr};
  opt.set_min_objective(nlopt_objective, &ctx);

  std::vector<double> y = y0;
  for (unsigned j = 0; j < n; ++j)
    y[j] = std::clamp(y[j], lo[j], hi[j]);
  double value = 0;
  OptimizerResult res;
  try
  {
    res.stop_reason = result_text(opt.optimize(y, value));
  }
  catch (const nlopt::roundoff_limited&)
  {
    res.stop_reason = "stopped: roundoff-limited (the misfit cannot be reduced further at this "
                      "precision)";
  }
  catch (const nlopt::forced_stop&)
  {
    if (ctx.error)
      std::rethrow_exception(ctx.error);
    throw;
  }
  catch (const std::exception& e)
  {
    if (ctx.error)
      std::rethrow_exception(ctx.error);
    throw std::runtime_error(std::string("NLopt failed: ") + e.what());
  }
  // The best evaluated point (gradient evaluations included).
  res.y = f.best_y();
  res.chi2 = f.best_chi2();
  return res;
}
} // namespace breastsim::calibration
