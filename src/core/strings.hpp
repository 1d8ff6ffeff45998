// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Small text helpers shared by the case reader and the command line.
#include <algorithm>
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

/// `text` for a message: at most `max` bytes, longer text cut with its length
/// stated ("1234567... (100000 bytes)"), so a huge value never floods the terminal.
inline std::string shorten(const std::string& text, std::size_t max = 80)
{
  if (text.size() <= max)
    return text;
  return text.substr(0, max) + "... (" + std::to_string(text.size()) + " bytes)";
}

/// The candidate closest to `word` by edit distance (insertions, deletions,
/// substitutions), if it is close enough to be a likely misspelling: at most
/// a third of the word's length, and at least 1. A candidate that is the word
/// with a suffix after '_' comes first (weight -> weight_kg: the key named
/// without its unit).
inline std::string closest_match(const std::string& word, const std::vector<std::string>& candidates)
{
  for (const auto& c : candidates)
    if (!word.empty() && c.size() > word.size() + 1 && c.compare(0, word.size(), word) == 0 && c[word.size()] == '_')
      return c;
  auto distance = [](const std::string& a, const std::string& b)
  {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
      row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
      std::size_t diagonal = row[0];
      row[0] = i;
      for (std::size_t j = 1; j <= b.size(); ++j)
      {
        const std::size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
        diagonal = up;
      }
    }
    return row[b.size()];
  };
  std::string best;
  std::size_t best_distance = std::max<std::size_t>(1, word.size() / 3) + 1;
  for (const auto& c : candidates)
    if (const std::size_t d = distance(word, c); d < best_distance)
    {
      best = c;
      best_distance = d;
    }
  return best;
}
} // namespace breastsim
