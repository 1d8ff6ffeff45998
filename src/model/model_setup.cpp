// SPDX-License-Identifier: LGPL-3.0-or-later
#include "model_setup.hpp"
#include "case_options.hpp"
#include "neutral_mesh.hpp"
#include "term_switches.hpp"
#include "errors.hpp"
#include <fmt/format.h>

namespace breastsim
{
void apply_parameters(const Config& c, Model& model)
{
  check_tissue_formulation(c);
  if ((CaseOptions::from(c).formulation == TissueFormulation::mixed) != model.mixed())
    throw InputError(fmt::format("key 'tissue.formulation' = \"{}\": this command builds {} models "
                                 "only (the mixed formulation runs in simulate and converge)",
                                 to_string(CaseOptions::from(c).formulation),
                                 model.mixed() ? "mixed" : "displacement"));
  for (const auto& k : schema())
  {
    if (k.ufl_name.empty())
      continue;
    if (k.type == KeyType::number)
      model.set_parameter(k.ufl_name, {c.number(k.key)});
    else
      model.set_parameter(k.ufl_name, c.numbers(k.key));
  }
  const TermSwitches terms = TermSwitches::from(c);
  for (const auto& t : model.term_names())
    model.set_term(t, terms.is_on(t));
}

std::unique_ptr<Model> make_neutral_model(const Config& c, MPI_Comm comm)
{
  auto m = std::make_unique<Model>(build_neutral_mesh(c, comm),
                                   Constraints{true, CaseOptions::from(c).fixed_base});
  apply_parameters(c, *m);
  return m;
}

double set_gravity(Model& model, const std::array<double, 3>& g)
{
  model.set_parameter("g_vec", {g[0], g[1], g[2]});
  model.set_parameter("load", {1.0});
  const double f_ext = model.residual_norm("gravity");
  model.set_parameter("load", {0.0});
  return f_ext;
}
} // namespace breastsim
