// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_id.hpp"
#include <random>

namespace breastsim::app
{
std::string new_job_id()
{
  static const char* hex = "0123456789abcdef";
  std::random_device rd;
  std::string id;
  for (int i = 0; i < 16; ++i)
    id += hex[rd() % 16];
  return id;
}

bool is_job_id(const std::string& id)
{
  if (id.size() != 16)
    return false;
  for (char c : id)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f')))
      return false;
  return true;
}
} // namespace breastsim::app
