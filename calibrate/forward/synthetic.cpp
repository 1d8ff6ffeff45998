// SPDX-License-Identifier: LGPL-3.0-or-later
#include "synthetic.hpp"
#include "case_options.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "posture_solve.hpp"
#include <fmt/format.h>
#include <random>

namespace breastsim::calibration
{
Config measure_truth(Config c, const MeasureRequest& r)
{
  c.set("geometry.mesh_size", r.mesh_size > 0 ? r.mesh_size : 0.5 * HalfCapSpec::from(c).mesh_size);
  c.validate();
  return c;
}

SyntheticOptions synthetic_options(const MeasureRequest& r)
{
  SyntheticOptions so;
  so.noise = r.noise;
  so.sigma = r.sigma > 0 ? r.sigma : (r.noise > 0 ? r.noise : 5e-4);
  so.seed = r.seed;
  return so;
}

nlohmann::json synthetic_measurements(const Config& truth, const SyntheticOptions& o, MPI_Comm comm)
{
  if (!(o.noise >= 0) || !(o.sigma > 0))
    throw InputError(fmt::format("synthetic measurements: noise = {} must be >= 0 and sigma = {} "
                                 "> 0 m",
                                 o.noise, o.sigma));
  const CaseOptions truth_case = CaseOptions::from(truth);
  Model model(build_neutral_mesh(truth, comm), Constraints{true, truth_case.fixed_base});
  apply_parameters(truth, model);
  NewtonSolver newton(model, NewtonOptions::from(truth));
  ObservableProbe probe(model, truth_case.geometry.nipple());
  // The same seed on every rank gives the same noise everywhere.
  std::mt19937 gen(o.seed);
  std::normal_distribution<double> noise(0.0, o.noise);
  auto noisy = [&](double x) { return o.noise > 0 ? x + noise(gen) : x; };

  nlohmann::json doc;
  doc["units"] = "SI";
  doc["sigma"] = o.sigma;
  doc["comment"] = fmt::format("synthetic: breastsim forward model, mesh_size {} m, noise {} m, "
                               "seed {}",
                               truth_case.geometry.mesh_size, o.noise, o.seed);
  doc["postures"] = nlohmann::json::array();
  for (const auto& p : requested_postures(truth))
  {
    log::info("synthetic measurements: solving posture '{}'", p.name);
    const Observables ob = solve_posture(model, newton, probe, p, truth).observables;
    nlohmann::json e;
    if (p.name.rfind("theta_", 0) == 0)
      e["theta_deg"] = p.theta_deg;
    else
      e["name"] = p.name;
    e["projection"] = noisy(ob.projection);
    e["z_min"] = noisy(ob.z_min);
    e["nipple"] = {noisy(ob.nipple[0]), noisy(ob.nipple[1]), noisy(ob.nipple[2])};
    if (p.theta_deg == 0)
    {
      // What is taken with a tape measure, standing.
      doc["base_perimeter"] = noisy(ob.base_perimeter);
      doc["breast_height"] = noisy(ob.z_max - ob.z_min);
    }
    else
      e["base_perimeter"] = noisy(ob.base_perimeter);
    doc["postures"].push_back(e);
  }
  return doc;
}
} // namespace breastsim::calibration
