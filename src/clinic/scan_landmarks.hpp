// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// A breast entered as a standing scan (docs/CLINIC.md, "A scanned breast"):
// the scan is framed and fitted as `scan-model` does (src/scan), and the
// clinic's tape measures are taken on its fitted skin: N-IMF along the skin
// in the nipple's sagittal plane down to the chest, the base width across
// the footprint, the projection, the ptosis grade from the nipple's height
// below the fold, and with a sternal notch landmark SN-N (the taut tape)
// and the nipple's distance from the midline. The patient model is fitted
// to these, and its standing skin is then compared with the scan's.
#include "landmarks.hpp"
#include "radial_fit.hpp"
#include "scan_frame.hpp"
#include "scan_surface.hpp"
#include "surface_export.hpp"
#include <filesystem>
#include <optional>
#include <nlohmann/json.hpp>

namespace breastsim::clinic
{
using Point = std::array<double, 3>;

/// The scan's fitted skin in its breast frame (y out of the chest plane, z
/// cranial, x lateral, origin the footprint's centre moved into the
/// nipple's sagittal plane x = 0).
struct ScannedSkin
{
  scan::BreastFrame frame;
  scan::RadialSurface fit;
  SkinSurface skin;          ///< the fit triangulated (reference = deformed, not a half model)
  Point nipple{};            ///< on the fitted skin [m]
  double volume = 0;         ///< under the fitted skin [m^3]
  double noise_rms = 0;      ///< robust RMS of the points about the fit [m]
  std::size_t points = 0;
};
/// Read, check and fit the scan (InputError as scan-model refuses it).
ScannedSkin read_scanned_skin(const SideScan& s);

/// The tape measures on a scanned skin; sn_n and nipple_midline only with a notch.
struct ScanMeasures
{
  SideLandmarks landmarks;
  Point fold{};                 ///< the meridian's end on the chest [m]
  std::vector<Point> n_imf_path; ///< from the nipple to the fold
  std::optional<Point> notch;   ///< on the chest plane, breast frame [m]
};
/// InputError when the notch lies lateral of the nipple or off the chest.
ScanMeasures measure_scan(const ScannedSkin& s, const std::optional<Point>& notch_scanner);

/// The landmarks the model is fitted to: those measured on the scan, SN-N
/// and the nipple's distance from the midline as entered unless a notch was
/// given. InputError when one lies outside its accepted range.
SideLandmarks scan_landmarks(const ScanMeasures& m, const SideLandmarks& entered, const std::filesystem::path& file);

/// How far the patient model's standing skin is from the scan: distances of
/// the scan's skin to the model's (the model moved so that both folds
/// coincide on the chest), area-weighted mean, 95th percentile and largest,
/// and both standing volumes.
struct ScanComparison
{
  double mean = 0, p95 = 0, max = 0;   ///< [m]
  double volume_scan = 0, volume_model = 0; ///< full breast [m^3]
  Point shift{};                       ///< model frame + shift = scan frame [m]
  /// (V_model - V_scan) / V_scan.
  double volume_error() const { return (volume_model - volume_scan) / volume_scan; }
};
/// `model`: the model's deformed standing skin (a half model is mirrored).
ScanComparison compare_with_scan(const ScannedSkin& s, const Point& scan_fold, const SkinSurface& model,
                                 const Point& model_fold);

/// The point of the scan's skin on the ray from the scan's base centre
/// through `p` + `shift` (model frame + shift = scan frame), back in the model's frame.
Point onto_scan(const ScannedSkin& s, const Point& shift, const Point& p);

/// Full-breast volume under a deformed skin and the chest plane y = 0:
/// V = sum over triangles of (n_y A) mean(y) (divergence theorem, the chest
/// contributes nothing), doubled for a half model.
double volume_under(const SkinSurface& s);

/// The scan's skin in the model's frame (scan frame - `shift`) for the 3D
/// view: {"vertices": [x, y, z, ...] [m, to 0.1 mm], "triangles": [i, j, k, ...], "mirror_x": false}.
nlohmann::json scan_surface_json(const ScannedSkin& s, const Point& shift);
/// One scanned side: the scan, what was measured on it, and the model against it.
struct ScanSide
{
  SideScan input;
  ScannedSkin skin;
  ScanMeasures measured;
  ScanComparison comparison;
  /// The sternal notch on the scan's chest plane: the landmark, or placed
  /// (as on the model) so that the taut tape over the scan has the entered SN-N.
  Point notch{};
};
/// The scan's file name, points and noise, the landmarks measured (mm) and
/// the model's distance from the scan (mm) and both volumes (cm^3).
nlohmann::json to_json(const ScanSide& s);
} // namespace breastsim::clinic
