// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Observables of a deformed breast (docs/MODEL.md), computed on the skin nodes:
// nipple position, projection (max y), z_min, z_max, base perimeter (full
// breast), volume (full breast) and total energy (full breast). A half model
// (with a symmetry face) is mirrored; a full breast is measured as it is.
#include "model.hpp"
#include <array>
#include <nlohmann/json.hpp>
#include <span>

namespace breastsim
{
struct Observables
{
  std::array<double, 3> nipple{};  ///< deformed position of the apex material point [m]
  double projection = 0;           ///< max y over the skin [m]
  double z_min = 0, z_max = 0;     ///< extreme z over the skin [m]
  double base_perimeter = 0;       ///< deformed base boundary, full breast [m]
  double volume = 0;               ///< deformed volume, full breast [m^3]
  double energy = 0;               ///< total potential energy, full breast [J]
};

nlohmann::json to_json(const Observables& o);

class ObservableProbe
{
public:
  /// `nipple_reference`: reference position of the nipple material point.
  ObservableProbe(const Model& model, std::array<double, 3> nipple_reference);
  /// Measure the model's current state (collective).
  Observables measure(Model& model) const;
  /// Directional derivative of the observables at the model's current state
  /// along the displacement change `du` (local and ghost dofs, the layout of
  /// displacement()->x()): d nipple = du at the apex node; projection, z_min,
  /// z_max (an extreme over the skin nodes) the derivative at the extreme
  /// node (exact where that node is unique); base perimeter the derivative
  /// of the polyline length. Volume and energy are not differentiated (NaN).
  /// Collective.
  Observables derivative(const Model& model, std::span<const double> du) const;
  /// Reference node coordinates (local nodes, row-major) of the skin.
  const std::vector<std::int32_t>& skin_nodes() const { return _skin; }

private:
  std::vector<double> _X;            // reference coordinates of all local nodes
  std::vector<std::int32_t> _skin;   // skin nodes
  std::vector<std::int32_t> _rim;    // nodes on base and skin
  int _apex_rank = 0;
  std::int32_t _apex_node = -1;      // on _apex_rank
  int _copies = 2;                   // 2: a half model (mirrored), 1: the full breast (no symmetry face)
};
} // namespace breastsim
