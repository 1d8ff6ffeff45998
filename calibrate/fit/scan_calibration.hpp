// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Calibration with scans (docs/SCANS.md "Calibration with scans"): the material parameters p (mu; c where the base springs are
// on) together with the stress-free neutral state, from scans of one breast
// in two or more postures, in one chest-fixed frame.
//
// For trial parameters p, the neutral state X(p) is the inverse solve
// (solver/inverse_neutral_state.hpp) from the first scan's mesh in its
// posture A; forward solves from X(p) to the postures of the other scans give
// their simulated skins, and each scan point's signed normal distance to its
// posture's simulated skin (forward/surface_distance.hpp), divided by that
// scan's noise sigma, is a residual. The sum of squares is minimised over
// y = ln p by fit/least_squares.hpp (Levenberg-Marquardt, forward-difference
// Jacobian), and the Gauss-Newton covariance gives the standard errors and
// 95 % intervals as `calibrate` reports them (fit/uncertainty.hpp). Points
// nearer the chest plane than `chest_margin` are left out (the rim, where the
// inverse keeps the base on the plane while the springs move it). A held-out
// scan is predicted from the fitted parameters and its RMS distance reported.
#include "config.hpp"
#include "fit_parameters.hpp"
#include "inverse_neutral_state.hpp"
#include "least_squares.hpp"
#include "output_target.hpp"
#include "posture.hpp"
#include "recording.hpp"
#include "tagged_mesh.hpp"
#include "uncertainty.hpp"
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace breastsim::calibration
{
/// One scan's points in the breast frame of the meshed scan.
struct ScanPoints
{
  std::string file;
  Posture posture;
  std::vector<Point> points; ///< [m]
  double sigma = 0.5e-3;     ///< noise standard deviation weighting its residuals [m]
};

struct ScanCalibrationRequest
{
  Config start;                ///< material and solver, the fitted keys' start values
  meshes::TaggedMesh mesh;     ///< the first scan's loaded shape (rank 0; breast frame)
  std::size_t nipple_node = 0; ///< its nipple node
  ScanPoints source;           ///< the first scan (posture A), for its report
  std::vector<ScanPoints> fit; ///< the other scans: fitted
  std::vector<ScanPoints> predict; ///< held out: predicted from the fit
  std::vector<FitParameter> parameters;
  InverseOptions inverse;
  LsqOptions lsq;
  double chest_margin = 0.005; ///< points nearer the chest plane y = 0 are not used [m]
  /// The discretisation error (as the diagnosis's mesh_error.cpp): the fit is
  /// repeated on `coarse_mesh`, the first scan meshed `mesh_ratio` times
  /// coarser, and SE_mesh(ln p) = |ln p - ln p_coarse| / (mesh_ratio - 1)
  /// (first-order convergence) widens each interval: SE = hypot(SE_noise,
  /// SE_mesh). mesh_ratio = 0: not estimated.
  meshes::TaggedMesh coarse_mesh;
  double mesh_ratio = 0;
};

/// Distances of one scan's points to its posture's simulated skin.
struct ScanDistance
{
  std::string file, posture;
  std::size_t points = 0, used = 0; ///< all, and those off the chest by chest_margin
  double rms = 0, max = 0;          ///< over the used points [m]
  double rms_all = 0;               ///< over all points [m]
  double sigma = 0;
};

struct ScanCalibrationResult
{
  std::vector<FitParameter> parameters;
  std::vector<double> start, value; ///< [unit]
  Uncertainty uncertainty;          ///< noise and, with mesh_ratio, the discretisation error
  std::vector<double> se_log_noise, se_log_mesh, coarse_value; ///< the parts of se_log; the coarse fit
  std::size_t tetrahedra = 0, coarse_tetrahedra = 0;
  double mesh_ratio = 0;
  double chi2 = 0, reduced_chi2 = 0;
  std::size_t residuals = 0;
  int evaluations = 0, iterations = 0;
  std::string stop_reason;
  std::vector<ScanDistance> at_start, fitted, predicted; ///< source scan first in fitted
  Config calibrated;               ///< start with the fitted values
  meshes::TaggedMesh reference;    ///< neutral state at the fitted values (rank 0; nipple on x = 0)
  std::array<double, 3> nipple{};  ///< in the reference [m]
  double shift_x = 0;              ///< x shift that keeps the nipple on x = 0 [m]
  InverseReport inverse;           ///< of the final neutral state
  double seconds = 0;
};

/// The whole fit (collective); throws SolveError when a solve fails.
ScanCalibrationResult scan_calibrate(const ScanCalibrationRequest& r, MPI_Comm comm);
/// report.json
nlohmann::json scan_calibration_json(const ScanCalibrationResult& r);
/// Write the result folder (staged, replaced only on success): report.json
/// (scan_calibration_json with `inputs`: the scans and their frame),
/// case.toml (the calibrated case on reference.msh: simulate, surgery, view
/// and calibrate accept it), reference.msh (the neutral state at the fitted
/// parameters) and scan.msh (the first scan's loaded mesh). Collective.
void write_scan_calibration(const ScanCalibrationRequest& r, const ScanCalibrationResult& res,
                            const nlohmann::json& inputs, const OutputTarget& out, MPI_Comm comm);
/// The console table.
std::string scan_calibration_table(const ScanCalibrationResult& r);
} // namespace breastsim::calibration
