// SPDX-License-Identifier: LGPL-3.0-or-later
#include "missing_physics.hpp"
#include "diagnosis_case.hpp"
#include "field_discovery.hpp"
#include "law_discovery.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <memory>
#include <optional>

namespace breastsim::diagnosis
{
void construct_missing_physics(PointEvaluator& ev, const Recording& rec, const std::vector<Free>& frees,
                               const FitState& state, const DiagnoseOptions& o, const Config& users,
                               Diagnosis& d)
{
  if (!o.discover)
    return;
  std::optional<FieldDiscovery> f;
  std::optional<LawDiscovery> l;
  if (o.discover_field)
    f = discover_field(ev, rec, frees, state, o);
  if (o.discover_law)
    l = discover_law(ev, rec, frees, state, o);
  if (f && l && f->accepted && l->accepted)
  {
    const bool field_wins = f->ridge.total_gain >= l->choice.total_gain;
    auto& loser = field_wins ? l->failed : f->failed;
    loser.push_back(fmt::format("the {} explains the held-out postures better (gain {:.1f} against {:.1f})",
                                field_wins ? "stiffness field" : "tissue law",
                                std::max(f->ridge.total_gain, l->choice.total_gain),
                                std::min(f->ridge.total_gain, l->choice.total_gain)));
    (field_wins ? l->accepted : f->accepted) = false;
  }
  if (f)
  {
    f->after.config = on_users_mesh(f->after.config, users);
    d.field = std::make_shared<const FieldDiscovery>(std::move(*f));
  }
  if (l)
  {
    l->after.config = on_users_mesh(l->after.config, users);
    d.law = std::make_shared<const LawDiscovery>(std::move(*l));
  }
}
} // namespace breastsim::diagnosis
