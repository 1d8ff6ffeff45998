// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Error types of breastsim. InputError: the user's input is wrong (exit code 2).
// SolveError: a physically or numerically impossible request (exit code 3).
#include <stdexcept>
#include <string>

namespace breastsim
{
/// Invalid user input: the message names the key, the value and the allowed range.
class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// A solve that failed even at the smallest allowed load step.
class SolveError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};
} // namespace breastsim
