// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A patient model per breast from the clinic's landmarks (docs/CLINIC.md,
// "Method"): the neutral cap's base radius R and height H (and a factor k
// on the tissue's and the skin's moduli when the ptosis grade is given) are fitted so that the simulated
// standing breast has the entered base width and N-IMF (and its nipple in
// the middle of the grade's height below the fold); the sternal
// notch is then placed on the chest so that the taut tape from it to the
// simulated nipple has the entered SN-N, at the entered distance of the
// nipple from the midline.
#include "config.hpp"
#include "landmarks.hpp"
#include "skin_measures.hpp"
#include <memory>
#include <mpi.h>

namespace breastsim::clinic
{
/// The landmarks of a simulated standing breast and where they lie.
struct StandingMeasures
{
  SideLandmarks landmarks;  ///< sn_n only once a notch is placed (else 0)
  Point nipple{}, fold{};   ///< deformed positions [m]
  int ptosis_grade = 0;     ///< from the nipple's height below the fold
};

/// Collective. The landmarks of a deformed half model's skin `s` (complete
/// on rank 0) with its nipple at `nipple`; SN-N from the notch
/// (notch_x, 0, notch_z) when `notch` is given.
StandingMeasures measure_standing(const SkinSurface& s, const Point& nipple, const Point* notch,
                                  MPI_Comm comm);

/// The height z of the sternal notch (at x = -nipple_midline on the chest)
/// whose taut tape to `nipple` has length `sn_n` (bisection; rank 0's
/// surface, the result on every rank). Throws InputError when SN-N is
/// shorter than the tape at the nipple's own height.
double place_notch(const SkinSurface& s, const Point& nipple, double nipple_midline, double sn_n,
                   MPI_Comm comm);

struct ScanSide; // scan_landmarks.hpp

struct SideModel
{
  std::string side;
  SideLandmarks target;
  Config config;            ///< the case with the fitted R, H (and moduli)
  Point notch{};            ///< the sternal notch in this breast's frame [m]
  StandingMeasures achieved;
  double largest_error = 0; ///< largest |achieved - target| over the fitted landmarks [m]
  int iterations = 0, solves = 0;
  double stiffness_factor = 1; ///< k on tissue.mu, tissue.lambda, skin.mu, skin.lambda (1: the case's)
  std::vector<std::string> notes; ///< e.g. the entered and the simulated ptosis grade differ
  SkinSurface standing;     ///< the fitted breast's standing skin (complete on rank 0)
  std::shared_ptr<const ScanSide> scan; ///< the side's scan, when it was given as one
};

/// Collective. Fit one breast (Levenberg-Marquardt on R, H, and log k when
/// the case's moduli do not give the entered ptosis grade; derivatives in R
/// and H by forward differences on the morphed mesh, in k from the tangent
/// of the converged solve). Stops when width and N-IMF are
/// within `tolerance` / 4 (and the nipple within 2 mm of its grade's
/// centre) or after 20 iterations. The fit moves one mesh (a morph); it is
/// then judged, and polished in up to 3 more rounds, on a mesh generated at
/// the fitted shape (the mesh the surgery solves), keeping the closest
/// round. Throws InputError when width or N-IMF
/// stays farther than `tolerance`, or the grade is not reached, naming the
/// landmark and how close it came. The projection is compared, not fitted.
SideModel fit_side(const Config& base, const std::string& side, const SideLandmarks& target,
                   double tolerance, MPI_Comm comm);
nlohmann::json to_json(const SideModel& m);
} // namespace breastsim::clinic
