#include "mesh_error.hpp"
#include "geometry_options.hpp"
#include "log.hpp"
#include <cmath>

namespace breastsim::calibration
{
Config finer(const Config& c, double ratio)
{
  Config f = c;
  f.set("geometry.mesh_size", HalfCapSpec::from(c).mesh_size / ratio);
  f.validate();
  return f;
}

std::vector<double> noise_floor(PointEvaluator& ev, PointEvaluator& fine_ev, const Recording& rec,
                                const FitState& state, double ratio, Diagnosis& d)
{
  log::info("numerical noise floor: solving the fitted model on a mesh {:g} times finer", ratio);
  const PointEvaluation ef = fine_ev(finer(state.config, ratio));
  const PointEvaluation ec = ev(state.config);
  std::vector<double> sigma;
  std::size_t k = 0;
  for (std::size_t p = 0; p < rec.postures.size(); ++p)
  {
    double ss = 0;
    const std::size_t n = rec.postures[p].points.size();
    for (std::size_t i = 0; i < n; ++i, ++k)
      ss += std::pow(ef.raw[k] - ec.raw[k], 2);
    d.mesh_error[p] = std::sqrt(ss / n);
    d.sigma_eff[p] = std::hypot(rec.noise_sigma, d.mesh_error[p]);
    sigma.insert(sigma.end(), n, d.sigma_eff[p]);
    log::info("numerical noise floor of posture '{}': {:.3f} mm (sigma_eff {:.3f} mm)",
              rec.postures[p].name, 1e3 * d.mesh_error[p], 1e3 * d.sigma_eff[p]);
  }
  for (const auto& P : rec.postures)
    if (P.nipple)
    {
      double ss = 0;
      for (int c = 0; c < 3; ++c, ++k)
        ss += std::pow(ef.raw[k] - ec.raw[k], 2);
      sigma.insert(sigma.end(), 3, std::hypot(rec.noise_sigma, std::sqrt(ss / 3)));
    }
  return sigma;
}

FitState with_numerical_uncertainty(const FitState& coarse, const FitState& fine, double ratio,
                                    std::vector<double>& se_numerical)
{
  FitState f = fine;
  f.config.set("geometry.mesh_size", HalfCapSpec::from(coarse.config).mesh_size); // the user's mesh
  auto& u = f.uncertainty;
  for (std::size_t i = 0; i < f.values.size() && i < u.se_log.size(); ++i)
  {
    const double se_num = std::abs(std::log(f.values[i] / coarse.values[i])) / (ratio - 1);
    se_numerical.push_back(se_num);
    widen_interval(u, i, f.values[i], se_num);
  }
  return f;
}
} // namespace breastsim::calibration
