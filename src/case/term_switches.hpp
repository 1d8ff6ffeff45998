// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The term switches terms.<term>, one per energy term generated from forms/
// (forms/registry.py), with the term's default.
#include "config.hpp"
#include <map>
#include <string>
#include <vector>

namespace breastsim
{
struct TermSwitches
{
  /// Term name -> switched on; every generated term, at its default.
  std::map<std::string, bool> on = generated_defaults();

  bool operator==(const TermSwitches&) const = default;
  /// Whether `term` is switched on; std::out_of_range for an unknown term.
  bool is_on(const std::string& term) const { return on.at(term); }
  /// Append terms.<term> for every generated term.
  static void declare(std::vector<KeyInfo>& keys);
  static TermSwitches from(const Config& c);
  /// Every generated term with its default switch.
  static std::map<std::string, bool> generated_defaults();
};
} // namespace breastsim
