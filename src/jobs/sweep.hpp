// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Incision sweeps: the surgery on a grid of incision parameters, reduced to
// one table row per combination.
#include "surgery.hpp"
#include <map>

namespace breastsim
{
struct SweepRow
{
  std::map<std::string, Value> parameters; ///< case key -> value (number, integer or boolean)
  bool ok = false;
  std::string error;                        ///< why the combination was rejected
  double resected_volume = 0;               ///< full breast [m^3]
  std::array<double, 3> nipple{};           ///< post-op standing nipple [m]
  double projection = 0, z_min = 0;         ///< post-op standing [m]
  /// Lower pole's share of the standing breast's volume in front of the
  /// chest wall, below the nipple (pole_volumes.hpp, the definition of the
  /// result tables): the aesthetic ideal is about 0.55 (upper:lower 45:55);
  /// a larger value is a bottomed-out, overfull lower pole.
  double lower_pole_share = 0;
  double max_gap = 0;
  int newton_iterations = 0;
  double seconds = 0;
  std::vector<PostureResult> pre, post; ///< the surgery's postures (Newton records)
};

/// Short names accepted by --vary (a, s, h, d) -> case keys; any other key
/// must be a number, integer or boolean key (InputError naming it otherwise).
std::string sweep_key(const std::string& name);
/// The values of `--vary key=v1,v2,...`, each parsed and range-checked as
/// the key's own type against `base`.
std::vector<Value> sweep_values(const Config& base, const std::string& key, const std::string& list);
using SweepGrid = std::vector<std::pair<std::string, std::vector<Value>>>;

/// Run the surgery for every combination of `grid` (case key -> values),
/// postures as in the case (standing must be among them: checked before any
/// solve). Each run writes into <out>/<label>/; the table into
/// <out>/sweep.json and sweep.csv.
/// InputError unless the grid has values and the postures include standing.
void check_sweep_request(const Config& base, const SweepGrid& grid);
/// `ranks_per_case` K: the ranks of `comm` split into groups of K, each
/// solving its share of the combinations (0: all ranks on each, in turn);
/// the table is complete on rank 0. `progress`: each combination of a
/// group's share (an equal part each), the surgery's stages inside it,
/// prefixed with the combination's label.
std::vector<SweepRow> sweep(const Config& base, const SweepGrid& grid, const OutputTarget& out,
                            MPI_Comm comm, int ranks_per_case = 0, const Progress& progress = {});
std::string sweep_table(const std::vector<SweepRow>& rows);
/// "key=value, ..." of a row's parameters.
std::string sweep_label(const SweepRow& row);
} // namespace breastsim
