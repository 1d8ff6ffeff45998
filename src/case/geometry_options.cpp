// SPDX-License-Identifier: LGPL-3.0-or-later
#include "geometry_options.hpp"
#include "errors.hpp"
#include <fmt/format.h>

namespace breastsim
{
void HalfCapSpec::declare(std::vector<KeyInfo>& keys)
{
  const HalfCapSpec d;
  keys.push_back(number_key("geometry.R", "m", d.R, 0.0, 0.5, "base radius of the neutral spherical cap", true));
  keys.push_back(number_key("geometry.H", "m", d.H, 0.0, 0.5,
                            "height of the neutral cap (nipple at (0, H, 0)); at most 1.5 R", true));
  keys.push_back(number_key("geometry.mesh_size", "m", d.mesh_size, 0.0, 0.1,
                            "target element size; between R/400 and min(R, H)/2", true));
  keys.push_back(number_key("geometry.rim_size_ratio", "1", d.rim_size_ratio, 0.1, 1.0,
                            "element size at the base rim (the inframammary fold) as a fraction of "
                            "mesh_size, graded to mesh_size within 2 mesh_size of the rim; 1: uniform "
                            "(the parametric cap; the incision's remeshing is uniform)"));
  keys.push_back(integer_key("geometry.order", d.order, 1, 2, "element (and geometry) order: 1 = P1, 2 = P2"));
  keys.push_back(integer_key("geometry.refinements", d.refinements, 0, 4, "uniform refinements of the gmsh mesh"));
  KeyInfo file = text_key("geometry.mesh_file", d.mesh_file,
                          "a tagged gmsh tetrahedral mesh (.msh; README, \"Your own mesh\") instead "
                          "of the parametric cap; \"\": the cap");
  file.path = true;
  keys.push_back(file);
  keys.push_back(number_key("geometry.nipple_z", "m", d.nipple_z, -0.5, 0.5,
                            "with geometry.mesh_file: z of the mesh's nipple node (0, H, nipple_z) "
                            "(the cap's nipple has z = 0)"));
}

HalfCapSpec HalfCapSpec::from(const Config& c)
{
  HalfCapSpec s;
  s.R = c.number("geometry.R");
  s.H = c.number("geometry.H");
  s.mesh_size = c.number("geometry.mesh_size");
  s.rim_size_ratio = c.number("geometry.rim_size_ratio");
  s.order = static_cast<int>(c.integer("geometry.order"));
  s.refinements = static_cast<int>(c.integer("geometry.refinements"));
  s.mesh_file = c.text("geometry.mesh_file");
  s.nipple_z = c.number("geometry.nipple_z");
  return s;
}

void HalfCapSpec::require_parametric_cap(const std::string& job) const
{
  if (!mesh_file.empty())
    throw InputError(fmt::format("key 'geometry.mesh_file' = \"{}\": {} needs the parametric cap "
                                 "(geometry.R, geometry.H); set geometry.mesh_file = \"\"",
                                 mesh_file, job));
}

void IncisionSpec::declare(std::vector<KeyInfo>& keys)
{
  const IncisionSpec d;
  keys.push_back(upper_bound_open(number_key(
      "incision.a_deg", "deg", d.a_deg, 0.0, 90.0,
      "surgery: angle a of plane P1 with the symmetry plane (90 deg would put the plane into the "
      "symmetry plane)",
      true)));
  keys.push_back(number_key("incision.s", "m", d.s, 0.0, 0.5,
                            "surgery: height s of the new nipple A above the base centre"));
  keys.push_back(number_key("incision.h", "m", d.h, 0.0, 0.5,
                            "surgery: height y_D = h of point D above the base", true));
  keys.push_back(number_key("incision.d", "m", d.d, 0.0, 0.5,
                            "surgery: depth of C = (0, 0, -d), the new inframammary fold"));
}

IncisionSpec IncisionSpec::from(const Config& c)
{
  IncisionSpec s;
  s.a_deg = c.number("incision.a_deg");
  s.s = c.number("incision.s");
  s.h = c.number("incision.h");
  s.d = c.number("incision.d");
  return s;
}
} // namespace breastsim
