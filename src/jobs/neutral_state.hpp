// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The `neutral-state` job: the case's geometry (its user mesh, or the cap) is
// a shape recorded in a loaded posture; the stress-free reference that the
// case's material and gravity deform into it is found by inverse
// elastostatics (solver/inverse_neutral_state.hpp) and written as a tagged
// mesh with a case that uses it.
//   reference.msh         the neutral (stress-free) mesh, groups tissue/base/skin (symmetry
//                         for a half model; a full breast is shifted along x to keep its
//                         nipple on x = 0, summary.json: reference_shift_x_m)
//   case.reference.toml   the case with geometry.mesh_file = "reference.msh" and
//                         the nipple (geometry.H, geometry.nipple_z) moved with it
//   summary.json          iterations (mismatch RMS/max, relaxation, Newton), time
#include "config.hpp"
#include "inverse_neutral_state.hpp"
#include "output_target.hpp"
#include "posture.hpp"
#include <array>
#include <mpi.h>
#include <string>

namespace breastsim
{
struct NeutralStateResult
{
  Posture posture;                 ///< the posture the shape was recorded in
  InverseReport inverse;
  std::array<double, 3> nipple{};  ///< the nipple in the neutral state [m]
  double max_node_shift = 0;       ///< largest |X - x_s| over the nodes [m]
  double shift_x = 0;              ///< full breast: x shift that keeps the nipple on x = 0 [m]
};

/// The whole job; writes into `out` (replaced only on success).
NeutralStateResult neutral_state(const Config& c, const Posture& posture, const InverseOptions& o,
                                 const OutputTarget& out, MPI_Comm comm);
std::string neutral_state_table(const NeutralStateResult& r);
} // namespace breastsim
