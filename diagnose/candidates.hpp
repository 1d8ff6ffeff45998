// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The library of physics a diagnosis may find missing: every energy term
// that declares a CANDIDATE in forms/ (forms/common.py candidate()), read from
// the generated registry. Each candidate is one registered term plus one
// scalar parameter q >= 0, nested in the current model: q = 0 reproduces the
// model without it (e.g. base_springs: q = 1/c, the compliance, q = 0 the
// fixed base; skin: q = mu_s, lambda_s keeping its ratio to mu_s).
// Adding a candidate: a CANDIDATE in the term's forms/<term>.py; no C++.
#include "breastsim_registry.hpp"
#include "config.hpp"
#include <string>
#include <utility>
#include <vector>

namespace breastsim::diagnosis
{
struct Candidate
{
  std::string name;      ///< the term's name (registry) = the candidate's name
  std::string parameter; ///< reported parameter, e.g. "ligament.k"
  std::string unit;
  std::string physics;   ///< what it stands for, in plain words
  double typical = 1;    ///< size of a clearly visible effect [unit]
  std::vector<generated::CandidateSetting> sets;   ///< the case keys q sets, in order
  std::vector<std::pair<std::string, bool>> flags; ///< case flags set with the term on
  std::string family; ///< the physics it names: its own name, or the candidate it is another form of
  /// The candidate it refines (a regional variation of that physics), or
  /// empty. An extension names its base's physics and applies only where
  /// the base term is on.
  std::string extends;
  /// Tested by a diagnosis that names no candidates (--candidates); false
  /// for a form kept available that its test did not admit.
  bool in_default_library = true;

  /// True if `other` is a form of the same physics (the same family).
  bool same_physics(const Candidate& other) const { return family == other.family; }

  /// True if the current case leaves this physics out (the term is off, or
  /// one of its flags has the other value, e.g. base.fixed = true) and has
  /// no other form of it switched on (one form per physics). An extension:
  /// true if its base is on and it is off.
  bool applicable(const Config& current) const;
  /// True if the term is on with every flag at its value.
  bool in_model(const Config& current) const;
  /// The current case with this physics switched on at q > 0.
  Config with(const Config& current, double q) const;
};

/// Every term's CANDIDATE, in the order of forms/registry.py.
const std::vector<Candidate>& candidate_library();
/// True if a diagnosis asked for the candidates `wanted` (--candidates;
/// empty: the default library) tests `c`.
bool is_wanted(const Candidate& c, const std::vector<std::string>& wanted);
/// Throws InputError for an unknown name (lists the library).
const Candidate& candidate(const std::string& name);
/// The physics the candidates `names` name when found (their families),
/// each once, in the order of `names`.
std::vector<std::string> physics_of(const std::vector<std::string>& names);
/// How many physics the terms `names` add: those that extend another
/// (a regional variation of a found physics) add none.
int physics_found(const std::vector<std::string>& names);
/// The candidates' names, comma separated (for help texts and messages).
std::string candidate_names();
/// The names of the candidates not in the default library, comma separated.
std::string candidates_not_default();
/// "name: parameter [unit]; ..." of every candidate (help texts).
std::string candidate_parameters();
} // namespace breastsim::diagnosis
