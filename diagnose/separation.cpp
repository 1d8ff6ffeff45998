// SPDX-License-Identifier: LGPL-3.0-or-later
#include "separation.hpp"
#include "candidates.hpp"
#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace breastsim::diagnosis
{
double separation_z(const FitState& a, const FitState& b, double margin_diff)
{
  const std::size_t n = std::min(a.r.size(), b.r.size());
  std::vector<double> d(n);
  double mean = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    d[i] = b.r[i] * b.r[i] - a.r[i] * a.r[i]; // d_i = r_B^2 - r_A^2
    mean += d[i] / static_cast<double>(n);
  }
  double ss = 0;
  for (double x : d)
    ss += (x - mean) * (x - mean);
  if (!(ss > 0))
    return margin_diff > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  return margin_diff / std::sqrt(ss); // z = (m_A - m_B) / sqrt(sum (d_i - mean d)^2)
}

std::vector<Rival> same_physics_rivals(const Round& r)
{
  std::vector<Rival> out;
  if (r.tested.empty())
    return out;
  const Candidate& a = candidate(r.tested);
  std::copy_if(r.rivals.begin(), r.rivals.end(), std::back_inserter(out),
               [&a](const Rival& x) { return a.same_physics(candidate(x.candidate)); });
  return out;
}

void set_aside_inseparable(Diagnosis& d)
{
  auto found = [&d](const std::string& name)
  { return std::find(d.discovered.begin(), d.discovered.end(), name) != d.discovered.end(); };
  for (const auto& r : d.rounds)
  {
    if (!r.accepted || r.rivals.empty() || !found(r.tested))
      continue;
    if (std::any_of(r.rivals.begin(), r.rivals.end(), [&](const Rival& x) { return found(x.candidate); }))
      continue;
    if (same_physics_rivals(r).size() == r.rivals.size())
      continue; // only other forms of the same physics: the physics is named
    Undecided u{r.tested, r.rivals};
    d.discovered.erase(std::find(d.discovered.begin(), d.discovered.end(), r.tested));
    d.undecided.push_back(u);
  }
}
} // namespace breastsim::diagnosis
