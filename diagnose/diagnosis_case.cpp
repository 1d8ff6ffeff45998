// SPDX-License-Identifier: LGPL-3.0-or-later
#include "diagnosis_case.hpp"
#include "fit_parameters.hpp"
#include <cstdint>

namespace breastsim::diagnosis
{
Config with_known(const Config& current, const Recording& rec, const DiagnoseOptions& o)
{
  Config c = current;
  for (const auto& [name, value] : rec.known)
    c.set(calibration::fit_alias(name).key, value);
  if (o.order > 0)
    c.set("geometry.order", std::int64_t(o.order));
  if (o.mesh_size > 0 && c.text("geometry.mesh_file").empty())
    c.set("geometry.mesh_size", o.mesh_size);
  c.validate();
  return c;
}

Config on_users_mesh(Config diagnosed, const Config& users)
{
  diagnosed.set("geometry.order", users.integer("geometry.order"));
  diagnosed.set("geometry.mesh_size", users.number("geometry.mesh_size"));
  diagnosed.validate();
  return diagnosed;
}
} // namespace breastsim::diagnosis
