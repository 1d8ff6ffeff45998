// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A discovered stiffness field written as a breastsim energy term: a UFL
// file that forms/ takes unchanged (the file plus its name in
// forms/registry.py),
//   E = int_B q (exp(s(X)) - 1) W(F; mu, lambda) dV,
// s(X) the discovered field with its amplitudes, centres and width as
// literals; q = 1 (the default) is the field as discovered, q = 0 the model
// without it, and q is the term's diagnosis candidate (not in the default
// library), so that later diagnoses can test the discovered physics again.
#include "field_discovery.hpp"
#include <string>

namespace breastsim::diagnosis
{
/// The term file's text; `name` a Python identifier (the term's NAME and
/// the prefix of its case keys), `source` what it was discovered on.
std::string field_term_source(const FieldDiscovery& f, const std::string& name, const std::string& source);
} // namespace breastsim::diagnosis
