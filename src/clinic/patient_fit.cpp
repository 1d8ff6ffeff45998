// SPDX-License-Identifier: LGPL-3.0-or-later
#include "patient_fit.hpp"
#include "scan_landmarks.hpp"
#include "errors.hpp"
#include "forward_model.hpp"
#include "least_squares.hpp"
#include "log.hpp"
#include "model.hpp"
#include "on_root.hpp"
#include "posture.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <memory>
#include <tuple>

namespace breastsim::clinic
{
using calibration::ForwardModel;

StandingMeasures measure_standing(const SkinSurface& s, const Point& nipple, const Point* notch, MPI_Comm comm)
{
  std::vector<double> v(10, 0.0);
  on_root(comm,
          [&]
          {
            Point fold{};
            v[0] = base_width(s);
            v[1] = nipple_to_fold(s, nipple, &fold);
            for (const auto& p : s.deformed)
              v[2] = std::max(v[2], p[1]); // projection: max y over the skin
            v[3] = notch ? taut_tape(s, *notch, nipple) : 0.0;
            std::copy(fold.begin(), fold.end(), v.begin() + 4);
          });
  MPI_Bcast(v.data(), static_cast<int>(v.size()), MPI_DOUBLE, 0, comm);
  StandingMeasures m;
  m.landmarks.base_width = v[0];
  m.landmarks.n_imf = v[1];
  m.landmarks.projection = v[2];
  m.landmarks.sn_n = v[3];
  m.nipple = nipple;
  m.fold = {v[4], v[5], v[6]};
  m.landmarks.nipple_midline = notch ? nipple[0] - (*notch)[0] : 0.0;
  m.ptosis_grade = ptosis_grade(m.fold[2] - nipple[2]);
  m.landmarks.ptosis_grade = m.ptosis_grade;
  return m;
}

double place_notch(const SkinSurface& s, const Point& nipple, double nipple_midline, double sn_n, MPI_Comm comm)
{
  double z = 0;
  on_root(comm,
          [&]
          {
            // The tape's length grows with the notch's height above the nipple.
            auto tape = [&](double zn) { return taut_tape(s, {nipple[0] - nipple_midline, 0, zn}, nipple); };
            double lo = nipple[2], hi = nipple[2] + 0.6;
            if (tape(lo) > sn_n)
              throw InputError(fmt::format(
                  "SN-N = {:.1f} cm is shorter than the tape from the midline to this nipple at its own "
                  "height ({:.1f} cm): with a nipple {:.1f} cm from the midline, SN-N must be longer",
                  100 * sn_n, 100 * tape(lo), 100 * nipple_midline));
            for (int k = 0; k < 60 && hi - lo > 1e-6; ++k)
              (tape(0.5 * (lo + hi)) < sn_n ? lo : hi) = 0.5 * (lo + hi);
            z = 0.5 * (lo + hi);
          });
  MPI_Bcast(&z, 1, MPI_DOUBLE, 0, comm);
  return z;
}

namespace
{
/// Height H of the cap of base radius R whose meridian from the apex to the
/// rim has length `arc`: rho = (R^2 + H^2) / 2H, arc = rho acos(1 - H / rho).
double cap_height_for_arc(double R, double arc)
{
  auto length = [R](double H)
  {
    const double rho = (R * R + H * H) / (2 * H);
    return rho * std::acos(1 - H / rho);
  };
  double lo = 0.2 * R, hi = 1.5 * R;
  for (int k = 0; k < 60; ++k)
    (length(0.5 * (lo + hi)) < arc ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

/// The nipple's height below the fold [m] in the middle of a ptosis grade's
/// interval (ptosis_grade()): 2 cm above the fold for grade 0, at the fold
/// for 1, 2 cm below for 2, 4 cm below for 3.
constexpr double min_factor = 0.02, max_factor = 20; ///< range of the stiffness factor k

double grade_centre(int grade)
{
  static const double centre[] = {-0.02, 0.0, 0.02, 0.04};
  return centre[grade];
}

/// The elastic moduli scaled by the stiffness factor k: tissue and skin mu
/// and lambda (the base springs keep the case's c). Scaling them all by k
/// is gravity scaled by 1/k in the body: k < 1 is a laxer breast that sags more.
const std::vector<std::string>& moduli()
{
  static const std::vector<std::string> keys = {"tissue.mu", "tissue.lambda", "skin.mu", "skin.lambda"};
  return keys;
}

/// One breast's fit: unknowns y = (R, H [, log k]), residuals [m]: base
/// width, N-IMF [, the nipple's height below the fold - the grade's centre].
class SideFit
{
public:
  /// `stiffness`: also fit the laxity k (needs the target's ptosis grade).
  SideFit(const Config& base, const SideLandmarks& t, MPI_Comm comm, bool stiffness)
      : _base(base), _target(t), _comm(comm), _forward({named_posture("standing")}, comm),
        _stiffness(stiffness && t.ptosis_grade.has_value())
  {
  }

  /// R and H rounded to 0.1 um: gmsh meshes two caps whose H differs in the
  /// last bit differently, and the fit's last bits depend on the order of
  /// parallel sums; rounded, 1 and 2 ranks mesh the same cap.
  Config config(const std::vector<double>& y) const
  {
    auto round = [](double v) { return std::round(v * 1e7) / 1e7; };
    const double R = round(y[0]);
    Config c = _base;
    c.set("geometry.R", R);
    c.set("geometry.H", std::min(round(y[1]), 1.5 * R)); // a cap's height is at most 1.5 R
    if (_stiffness)
      for (const auto& key : moduli())
        c.set(key, std::exp(y[2]) * _base.number(key));
    return c;
  }

  std::vector<double> clamp(std::vector<double> y) const
  {
    y[0] = std::clamp(y[0], 0.035, 0.15);
    const double h_min = std::max(0.2 * y[0], 2.5 * _base.number("geometry.mesh_size"));
    y[1] = std::clamp(y[1], h_min, 1.5 * y[0]);
    if (_stiffness)
      y[2] = std::clamp(y[2], std::log(min_factor), std::log(max_factor));
    return y;
  }

  std::vector<double> initial() const
  {
    const double R = 0.5 * _target.base_width;
    std::vector<double> y = {R, cap_height_for_arc(R, _target.n_imf)};
    if (_stiffness)
      y.push_back(0.0);
    return clamp(y);
  }

  /// Solve standing at y; the measures and the residuals.
  std::pair<StandingMeasures, std::vector<double>> evaluate(const std::vector<double>& y)
  {
    const Config c = config(y);
    c.validate();
    SkinSurface s;
    _forward.prepare(c);
    const Observables o = _forward.solve_posture(0, c, [&](std::size_t, const Model& m) { s = gather_skin_surface(m); });
    ++_solves;
    _surface = s;
    const StandingMeasures m = measure_standing(s, o.nipple, nullptr, _comm);
    return {m, residuals(m)};
  }

  std::vector<double> residuals(const StandingMeasures& m) const
  {
    std::vector<double> r = {m.landmarks.base_width - _target.base_width, m.landmarks.n_imf - _target.n_imf};
    if (_stiffness)
      r.push_back((m.fold[2] - m.nipple[2]) - grade_centre(*_target.ptosis_grade));
    return r;
  }

  /// d residuals / d log k at the equilibrium of y, from du/dlog k = -K^{-1} dR/dlog k
  /// (dR/dlog k: the residual difference of the cases at log k +- 1e-4).
  std::vector<double> stiffness_column(const std::vector<double>& y, const StandingMeasures& at)
  {
    const double h = 1e-4;
    std::vector<double> yp = y, ym = y;
    yp[2] += h;
    ym[2] -= h;
    std::vector<double> col;
    _forward.sensitivities(0, config(y), {{config(yp), config(ym), 2 * h}},
                           [&](std::size_t, const Model& model, std::span<const double> du, const Observables& d)
                           {
                             // The measures along u + eps du: geometry only, no solve.
                             const double eps = 1e-4;
                             const auto u = model.displacement()->x()->array();
                             std::vector<double> moved(u.begin(), u.end());
                             for (std::size_t k = 0; k < moved.size(); ++k)
                               moved[k] += eps * du[k];
                             Point nipple = at.nipple;
                             for (int k = 0; k < 3; ++k)
                               nipple[k] += eps * d.nipple[k];
                             const auto r1 = residuals(measure_standing(gather_skin_surface(model, moved), nipple,
                                                                        nullptr, _comm));
                             const auto r0 = residuals(at);
                             for (std::size_t k = 0; k < r0.size(); ++k)
                               col.push_back((r1[k] - r0[k]) / eps);
                           });
    return col;
  }

  bool fits_stiffness() const { return _stiffness; }
  int solves() const { return _solves; }
  const SkinSurface& surface() const { return _surface; }

private:
  Config _base;
  SideLandmarks _target;
  MPI_Comm _comm;
  ForwardModel _forward;
  bool _stiffness;
  int _solves = 0;
  SkinSurface _surface;
};

double largest(const std::vector<double>& r)
{
  double m = 0;
  for (double x : r)
    m = std::max(m, std::abs(x));
  return m;
}

double norm2(const std::vector<double>& r)
{
  double s = 0;
  for (double x : r)
    s += x * x;
  return s;
}

/// The Levenberg-Marquardt step (J^T J + lambda diag(J^T J)) dy = -J^T r
/// (J stored by columns); zero if J^T J is singular (the caller then damps more).
std::vector<double> lm_step(const std::vector<std::vector<double>>& J, const std::vector<double>& r, double lambda)
{
  const std::size_t n = J.size();
  calibration::Matrix A(n, std::vector<double>(n, 0.0));
  std::vector<double> g(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = 0; k < r.size(); ++k)
        A[i][j] += J[i][k] * J[j][k];
    for (std::size_t k = 0; k < r.size(); ++k)
      g[i] += J[i][k] * r[k];
  }
  return calibration::gauss_newton_step(A, g, lambda).value_or(std::vector<double>(n, 0.0));
}
} // namespace

namespace
{
/// J = dr/dy at y: k from the tangent at y's equilibrium (the last solve,
/// so taken first: no solve), then R and H, which move the mesh (forward
/// differences on the morph, backward at an upper bound).
std::vector<std::vector<double>> jacobian(SideFit& fit, const std::vector<double>& y, const std::vector<double>& r,
                                          const StandingMeasures& m)
{
  std::vector<std::vector<double>> J(2);
  if (fit.fits_stiffness())
    J.push_back(fit.stiffness_column(y, m));
  for (int k = 0; k < 2; ++k)
  {
    std::vector<double> yk = y;
    yk[k] += 5e-4;
    const double h = fit.clamp(yk)[k] == yk[k] ? 5e-4 : -5e-4;
    yk[k] = y[k] + h;
    const auto rk = fit.evaluate(yk).second;
    J[k].resize(r.size());
    for (std::size_t i = 0; i < r.size(); ++i)
      J[k][i] = (rk[i] - r[i]) / h;
  }
  return J;
}

/// One Levenberg-Marquardt move: steps of growing damping until one lowers
/// |r| (y, m, r updated; false if none does in 8 tries). A trust region: at
/// most 1 cm in R and H and a factor 2 in k per step.
bool lm_move(SideFit& fit, const std::vector<std::vector<double>>& J, std::vector<double>& y, StandingMeasures& m,
             std::vector<double>& r, double& lambda, const std::string& side)
{
  for (int attempt = 0; attempt < 8; ++attempt)
  {
    const auto step = lm_step(J, r, lambda);
    const double scale = std::min({1.0, 0.01 / std::max(std::abs(step[0]), 1e-12),
                                   0.01 / std::max(std::abs(step[1]), 1e-12),
                                   step.size() > 2 ? std::log(2.0) / std::max(std::abs(step[2]), 1e-12) : 1.0});
    std::vector<double> trial = y;
    for (std::size_t k = 0; k < y.size(); ++k)
      trial[k] += scale * step[k];
    trial = fit.clamp(trial);
    try
    {
      auto [mt, rt] = fit.evaluate(trial);
      if (norm2(rt) < norm2(r))
      {
        y = trial, m = mt, r = rt;
        lambda = std::max(lambda / 3, 1e-6);
        return true;
      }
    }
    catch (const SolveError& e)
    {
      log::debug("patient {}: trial not solved ({})", side, e.what());
    }
    lambda *= 4;
  }
  return false;
}

/// InputError when width or N-IMF is farther than the tolerance, or the grade
/// is missed; `morph_miss`: the largest width or N-IMF error on the fit's own (morphed) mesh.
void check_reached(const SideModel& out, const std::vector<double>& rr, const std::vector<double>& y,
                   double tolerance, double morph_miss)
{
  const auto& target = out.target;
  const char* names[] = {"base width", "N-IMF"};
  std::string missed;
  for (std::size_t k = 0; k < 2; ++k)
  {
    const double wanted = k == 0 ? target.base_width : target.n_imf;
    if (std::abs(rr[k]) > tolerance)
      missed += fmt::format("{}{} of {:.1f} cm (the closest it came is {:.1f} cm)", missed.empty() ? "" : " and ",
                            names[k], 100 * wanted, 100 * (wanted + rr[k]));
  }
  if (!missed.empty() && morph_miss <= tolerance) // the shape fits; the generated mesh does not
    throw InputError(fmt::format("patient {}: the entered {} is reached within {:.2f} mm on the fitted (morphed) mesh "
                                 "but not within {:.1f} mm on meshes generated at that shape (the surgery's): the "
                                 "mesh is too coarse for this tolerance with this breast (geometry.mesh_size = "
                                 "{:.1f} mm); use a finer mesh or a larger --tolerance",
                                 out.side, missed, 1e3 * morph_miss, 1e3 * tolerance,
                                 1e3 * out.config.number("geometry.mesh_size")));
  if (!missed.empty())
    throw InputError(fmt::format("patient {}: the model cannot reach the entered {} within {:.1f} mm (R = {:.1f} mm, "
                                 "H = {:.1f} mm{}; a cap's height is at most 1.5 R)",
                                 out.side, missed, 1e3 * tolerance, 1e3 * y[0], 1e3 * y[1],
                                 y.size() > 2 ? fmt::format(", stiffness x {:.3g}", std::exp(y[2])) : ""));
  const auto& a = out.achieved;
  if (target.ptosis_grade && *target.ptosis_grade != a.ptosis_grade)
    throw InputError(fmt::format("patient {}: the model cannot reach the entered ptosis grade {}: with its moduli "
                                 "scaled by {} to {} its standing nipple lies at best {:.1f} cm {} the fold (grade {})",
                                 out.side, *target.ptosis_grade, min_factor, max_factor,
                                 100 * std::abs(a.fold[2] - a.nipple[2]), a.nipple[2] < a.fold[2] ? "below" : "above",
                                 a.ptosis_grade));
}

/// What the model does not reproduce by design: the projection, a notch below the base.
void add_notes(SideModel& out, double tolerance)
{
  const auto& t = out.target;
  const auto& a = out.achieved.landmarks;
  if (t.projection && std::abs(*a.projection - *t.projection) > tolerance)
    out.notes.push_back(fmt::format("entered projection {:.1f} cm, simulated {:.1f} cm: the model's breast shape ties "
                                    "projection to width and nipple-to-fold length, so the projection is compared, "
                                    "not fitted",
                                    100 * *t.projection, 100 * *a.projection));
  if (out.notch[2] < out.config.number("geometry.R"))
    out.notes.push_back(fmt::format("the sternal notch lies {:.1f} cm above the base centre, below the base's upper "
                                    "edge ({:.1f} cm): SN-N is short for this breast",
                                    100 * out.notch[2], 100 * out.config.number("geometry.R")));
}
} // namespace

namespace
{
/// Levenberg-Marquardt on `fit` from y until `done` or 20 moves; returns the moves made.
int lm_fit(SideFit& fit, std::vector<double>& y, StandingMeasures& m, std::vector<double>& r,
           const std::function<bool(const std::vector<double>&)>& done, const std::string& side)
{
  double lambda = 1e-3;
  int it = 0;
  for (; it < 20 && !done(r); ++it)
  {
    if (!lm_move(fit, jacobian(fit, y, r, m), y, m, r, lambda, side))
      break;
    log::info("patient {}: iteration {}: width {:.1f} mm, N-IMF {:.1f} mm, largest error {:.2f} mm", side, it + 1,
              1e3 * m.landmarks.base_width, 1e3 * m.landmarks.n_imf, 1e3 * largest(r));
  }
  return it;
}
} // namespace

SideModel fit_side(const Config& base, const std::string& side, const SideLandmarks& target, double tolerance,
                   MPI_Comm comm)
{
  // Done when width and N-IMF are within a quarter of the tolerance and the
  // nipple within 2 mm of its grade's centre.
  auto done = [&](const std::vector<double>& res)
  {
    return std::abs(res[0]) <= tolerance / 4 && std::abs(res[1]) <= tolerance / 4 &&
           (res.size() < 3 || std::abs(res[2]) <= 2e-3);
  };
  // The fit moves one mesh onto each shape (morph); the surgery meshes the
  // final shape afresh, and a soft breast's landmarks differ by millimetres
  // between two meshes of one size. So the fit is judged, and polished, on a
  // mesh generated at its final shape: the mesh every later job solves.
  // The laxity k is fitted only when the case's moduli do not give the entered grade.
  bool lax = false;
  auto fit = std::make_unique<SideFit>(base, target, comm, lax);
  std::vector<double> y = fit->initial();
  auto [m, r] = fit->evaluate(y);
  int it = lm_fit(*fit, y, m, r, done, side), solves = 0;
  if (target.ptosis_grade && m.ptosis_grade != *target.ptosis_grade)
  {
    log::info("patient {}: grade {} with the case's moduli, {} entered: fitting the laxity", side, m.ptosis_grade,
              *target.ptosis_grade);
    solves += fit->solves();
    lax = true;
    fit = std::make_unique<SideFit>(base, target, comm, lax);
    y.push_back(0.0);
    std::tie(m, r) = fit->evaluate(y);
    it += lm_fit(*fit, y, m, r, done, side);
  }
  const double morph_miss = std::max(std::abs(r[0]), std::abs(r[1]));
  // Of the fresh meshes, the one whose landmarks come closest.
  struct Fresh
  {
    std::vector<double> y;
    StandingMeasures m;
    SkinSurface surface;
    double miss = std::numeric_limits<double>::infinity();
  } best;
  const int rounds = 4;
  for (int round = 0; round < rounds; ++round)
  {
    solves += fit->solves();
    fit = std::make_unique<SideFit>(base, target, comm, lax);
    std::tie(m, r) = fit->evaluate(y);
    // As check_reached judges: width and N-IMF, and the grade itself (not its centre).
    const double miss = std::max(std::abs(r[0]), std::abs(r[1])) +
                        (target.ptosis_grade && m.ptosis_grade != *target.ptosis_grade ? 1.0 : 0.0);
    if (miss < best.miss)
      best = {y, m, fit->surface(), miss};
    if (done(r) || round == rounds - 1)
      break;
    log::info("patient {}: the mesh generated at the fitted shape misses by {:.2f} mm; fitting on it", side,
              1e3 * largest(r));
    it += lm_fit(*fit, y, m, r, done, side);
  }
  SideModel out;
  out.side = side;
  out.target = target;
  out.config = fit->config(best.y);
  out.stiffness_factor = fit->fits_stiffness() ? std::exp(best.y[2]) : 1.0;
  out.iterations = it;
  const double notch_z = place_notch(best.surface, best.m.nipple, target.nipple_midline, target.sn_n, comm);
  out.notch = {best.m.nipple[0] - target.nipple_midline, 0.0, notch_z};
  out.achieved = measure_standing(best.surface, best.m.nipple, &out.notch, comm);
  out.solves = solves + fit->solves();
  const auto rr = fit->residuals(out.achieved);
  check_reached(out, rr, best.y, tolerance, morph_miss);
  out.largest_error = std::max({std::abs(rr[0]), std::abs(rr[1]), std::abs(out.achieved.landmarks.sn_n - target.sn_n)});
  add_notes(out, tolerance);
  out.standing = std::move(best.surface);
  return out;
}

nlohmann::json to_json(const SideModel& m)
{
  nlohmann::json j = {{"side", m.side},
          {"target", to_json(m.target)},
          {"achieved", to_json(m.achieved.landmarks)},
          {"largest_error_mm", 1e3 * m.largest_error},
          {"R_m", m.config.number("geometry.R")},
          {"H_m", m.config.number("geometry.H")},
          {"tissue_mu_Pa", m.config.number("tissue.mu")},
          {"stiffness_factor", m.stiffness_factor},
          {"notch_m", m.notch},
          {"nipple_standing_m", m.achieved.nipple},
          {"fold_standing_m", m.achieved.fold},
          {"iterations", m.iterations},
          {"solves", m.solves},
          {"notes", m.notes}};
  if (m.scan)
    j["scan"] = to_json(*m.scan);
  return j;
}
} // namespace breastsim::clinic
