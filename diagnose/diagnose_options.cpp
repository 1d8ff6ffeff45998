// SPDX-License-Identifier: LGPL-3.0-or-later
// The diagnosis options' ranges (diagnosis.hpp), checked once at the edge.
#include "candidates.hpp"
#include "diagnosis.hpp"
#include "errors.hpp"
#include <fmt/format.h>

namespace breastsim::diagnosis
{
void check(const DiagnoseOptions& o)
{
  for (const auto& name : o.candidates)
    candidate(name); // unknown names: InputError
  if (!(o.alpha > 0 && o.alpha < 0.5))
    throw InputError(fmt::format("--alpha = {} is out of range: allowed (0, 0.5)", o.alpha));
  if (o.refits < 1 || o.refits > 10)
    throw InputError(fmt::format("--refits = {} is out of range: allowed [1, 10]", o.refits));
  if (o.mesh_ratio > 4)
    throw InputError(fmt::format("--mesh-ratio = {} is out of range: allowed <= 1 (off) or (1, 4]",
                                 o.mesh_ratio));
  if (!(o.min_effect >= 0 && o.min_effect <= 5))
    throw InputError(fmt::format("--min-effect = {} is out of range: allowed [0, 5]", o.min_effect));
  if (!(o.min_misfit_share >= 0 && o.min_misfit_share < 1))
    throw InputError(fmt::format("--min-misfit-share = {} is out of range: allowed [0, 1) (0: off)",
                                 o.min_misfit_share));
  if (!(o.min_misfit_share_later >= 0 && o.min_misfit_share_later < 1))
    throw InputError(fmt::format("--min-misfit-share-later = {} is out of range: allowed [0, 1) (0: off)",
                                 o.min_misfit_share_later));
  if (!(o.min_score_fraction >= 0 && o.min_score_fraction <= 1))
    throw InputError(fmt::format("--min-score-fraction = {} is out of range: allowed [0, 1] (0: off)",
                                 o.min_score_fraction));
  if (!(o.refinement_order >= 0 && o.refinement_order <= 4))
    throw InputError(fmt::format("--refinement-order = {} is out of range: allowed [0, 4] (0: off)",
                                 o.refinement_order));
  if (o.order < 0 || o.order > 2)
    throw InputError(fmt::format("--order = {} is out of range: allowed 1, 2 (0: the case's)", o.order));
  if (!(o.mesh_size >= 0 && o.mesh_size <= 0.1))
    throw InputError(fmt::format("--mesh-size = {} m is out of range: allowed (0, 0.1] (0: the case's)",
                                 o.mesh_size));
  if (!(o.min_separation_z >= 0 && o.min_separation_z <= 10))
    throw InputError(fmt::format("--min-separation-z = {} is out of range: allowed [0, 10] (0: off)",
                                 o.min_separation_z));
  if (o.jackknife_patches < 0 || o.jackknife_patches > 10)
    throw InputError(fmt::format("--jackknife-patches = {} is out of range: allowed [0, 10] (0: off)",
                                 o.jackknife_patches));
  if (o.max_rounds < 1 || o.max_rounds > 10)
    throw InputError(fmt::format("--max-rounds = {} is out of range: allowed [1, 10]", o.max_rounds));
}
} // namespace breastsim::diagnosis
