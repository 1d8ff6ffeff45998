#pragma once
// The library of physics a diagnosis may find missing (issue 7). Each
// candidate is one registered energy term plus one scalar parameter q >= 0,
// nested in the current model: q = 0 reproduces the model without it.
//   base_springs        q = 1/c, compliance of the Chassaignac space [m/Pa]
//                       (q = 0: the fixed base; q > 0: springs c = 1/q)
//   skin                q = mu_s [Pa] (lambda_s = mu_s x the case's ratio)
//   suspensory_ligament q = k_l [Pa/m] on the upper-pole skin
//   gland_core          q = m_g, extra stiffness of the central gland
// Adding a candidate: one UFL term (forms/) and one entry in the table of
// candidates.cpp.
#include "config.hpp"
#include <string>
#include <vector>

namespace breastsim::calibration
{
struct Candidate
{
  std::string name;      ///< the term's name (registry) = the candidate's name
  std::string parameter; ///< reported parameter, e.g. "ligament.k"
  std::string unit;
  std::string physics;   ///< what it stands for, in plain words
  double typical = 1;    ///< size of a clearly visible effect [unit]

  /// True if the current case leaves this physics out (the term is off).
  bool applicable(const Config& current) const;
  /// The current case with this physics switched on at q > 0.
  Config with(const Config& current, double q) const;
};

const std::vector<Candidate>& candidate_library();
/// Throws InputError for an unknown name (lists the library).
const Candidate& candidate(const std::string& name);
} // namespace breastsim::calibration
