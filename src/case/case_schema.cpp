// SPDX-License-Identifier: LGPL-3.0-or-later
// schema() (schema.hpp): the option structs' declarations, section by
// section, then the physics parameters and term switches generated from
// forms/. A unit without a header: the option structs read a Config, and
// Config reads the schema.
#include "breastsim_registry.hpp"
#include "case_options.hpp"
#include "output_options.hpp"
#include "schema.hpp"
#include "solver_options.hpp"
#include "surgery_options.hpp"
#include "term_switches.hpp"
#include <algorithm>

namespace breastsim
{
namespace
{
/// The physics parameters generated from forms/; a key already declared
/// (a geometry key also bound into the forms) gets its UFL name.
void add_generated_parameters(std::vector<KeyInfo>& s)
{
  for (const auto& p : generated::parameters())
  {
    if (p.key.empty())
      continue;
    auto it = std::find_if(s.begin(), s.end(), [&](const KeyInfo& k) { return k.key == p.key; });
    if (it != s.end())
    {
      it->ufl_name = p.name; // a geometry key also bound into the forms
      continue;
    }
    KeyInfo k;
    k.key = p.key;
    k.unit = p.unit;
    k.lo = p.lo;
    k.hi = p.hi;
    k.lo_open = p.lo_open;
    k.doc = p.doc + " [term: " + p.term + "]";
    k.ufl_name = p.name;
    if (p.default_value.size() == 1)
    {
      k.type = KeyType::number;
      k.default_value = p.default_value[0];
    }
    else
    {
      k.type = KeyType::number_list;
      k.default_value = p.default_value;
      k.size = p.default_value.size();
    }
    s.push_back(k);
  }
}

std::vector<KeyInfo> build_schema()
{
  std::vector<KeyInfo> s;
  CaseOptions::declare(s);
  SolverOptions::declare(s);
  SurgeryOptions::declare(s);
  OutputOptions::declare(s);
  add_generated_parameters(s);
  TermSwitches::declare(s);
  return s;
}
} // namespace

const std::vector<KeyInfo>& schema()
{
  static const std::vector<KeyInfo> s = build_schema();
  return s;
}
} // namespace breastsim
