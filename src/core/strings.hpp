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

namespace breastsim
{
/// `text` for a message: at most `max` bytes, longer text cut with its length
/// stated ("1234567... (100000 bytes)"), so a huge value never floods the terminal.
inline std::string shorten(const std::string& text, std::size_t max = 80)
{
  if (text.size() <= max)
    return text;
  return text.substr(0, max) + "... (" + std::to_string(text.size()) + " bytes)";
}
} // namespace breastsim
