// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The message of the InputError a call throws ("" if it throws none): tests
// compare the messages users see.
#include "errors.hpp"
#include <functional>
#include <string>

namespace breastsim::fixtures
{
inline std::string message_of(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace breastsim::fixtures
