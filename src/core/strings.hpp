#pragma once
// Small text helpers shared by the case reader and the command line.
#include <sstream>
#include <string>
#include <vector>

namespace breastsim
{
/// The non-empty items of a separated list: "a,,b" -> {"a", "b"}.
inline std::vector<std::string> split_list(const std::string& text, char separator = ',')
{
  std::vector<std::string> items;
  std::string item;
  std::istringstream is(text);
  while (std::getline(is, item, separator))
    if (!item.empty())
      items.push_back(item);
  return items;
}
} // namespace breastsim
