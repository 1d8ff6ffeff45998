// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The geometry keys of a case: the neutral half cap (geometry.*) and the
// incision of the surgery (incision.*), each a plain struct that declares
// its keys for the schema and reads them from a Config.
#include "config.hpp"
#include <array>
#include <string>
#include <vector>

namespace breastsim
{
/// The neutral half cap (docs/MODEL.md): base radius R, height H (nipple at
/// (0, H, 0)), and its mesh.
struct HalfCapSpec
{
  double R = 0.07;          ///< base radius [m]
  double H = 0.06;          ///< height of the cap (apex y) [m]
  double mesh_size = 0.008; ///< target element size [m]
  /// Element size at the base rim (the inframammary fold) as a fraction of
  /// mesh_size, graded to mesh_size away from it; 1: uniform.
  double rim_size_ratio = 1.0;
  int order = 1;            ///< geometry/element order (1 or 2)
  int refinements = 0;      ///< uniform refinements after meshing
  /// A user's tagged gmsh mesh instead of the parametric cap ("": the cap);
  /// R and H then describe it (H: the height of its nipple node (0, H, 0)).
  std::string mesh_file;
  double nipple_z = 0;      ///< z of the nipple node (0, H, nipple_z) of a user mesh [m]

  bool operator==(const HalfCapSpec&) const = default;
  /// Append geometry.R, geometry.H, geometry.mesh_size, geometry.rim_size_ratio,
  /// geometry.order, geometry.refinements, geometry.mesh_file (defaults: the
  /// initialisers above).
  static void declare(std::vector<KeyInfo>& keys);
  static HalfCapSpec from(const Config& c);
  /// The nipple in the neutral state: (0, H, nipple_z).
  std::array<double, 3> nipple() const { return {0.0, H, nipple_z}; }
  /// Throws InputError when a user mesh is set: `job` needs the parametric cap.
  void require_parametric_cap(const std::string& job) const;
};

/// The incision parameters (docs/MODEL.md, "Incision").
struct IncisionSpec
{
  double a_deg = 30.0; ///< angle a of P1 with the symmetry plane [deg]
  double s = 0.02;     ///< height of the new nipple A above the base centre [m]
  double h = 0.025;    ///< height y_D of D above the base [m]
  double d = 0.045;    ///< depth of C = (0, 0, -d) below the base centre [m]

  bool operator==(const IncisionSpec&) const = default;
  /// Append incision.a_deg, incision.s, incision.h, incision.d.
  static void declare(std::vector<KeyInfo>& keys);
  static IncisionSpec from(const Config& c);
};
} // namespace breastsim
