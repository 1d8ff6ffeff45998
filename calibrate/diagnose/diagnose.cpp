#include "diagnose.hpp"
#include "errors.hpp"
#include "fit_parameters.hpp"
#include "log.hpp"
#include "surface_distance.hpp"
#include "surface_export.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <memory>

namespace breastsim::calibration
{
namespace
{
const double nan = std::numeric_limits<double>::quiet_NaN();

/// A free parameter of a fit: p = exp(y) within [lo, hi], written into a case by `set`.
struct Free
{
  std::string name, unit;
  double lo = 0, hi = 0;
  std::function<void(Config&, double)> set;
  double start = 1; ///< starting value [unit]
};

std::vector<Free> frees_from_fit(const std::string& list, const Config& c)
{
  std::vector<Free> out;
  if (list.empty())
    return out;
  for (const auto& p : parse_fit(list, c))
  {
    const std::string key = p.key;
    out.push_back({p.name, p.unit, p.lower, p.upper, [key](Config& c, double v) { c.set(key, v); },
                   c.number(key)});
  }
  return out;
}

Free free_candidate(const Candidate& cand)
{
  return {cand.parameter, cand.unit, cand.typical * 1e-4, cand.typical * 1e3,
          [&cand](Config& c, double v) { c = cand.with(c, v); }, cand.typical};
}

Config config_at(const Config& base, const std::vector<Free>& frees, const std::vector<double>& y)
{
  Config c = base;
  for (std::size_t i = 0; i < frees.size(); ++i)
    frees[i].set(c, std::exp(y[i]));
  c.validate();
  return c;
}

/// One forward evaluation: distances of the recorded points, landmark errors.
struct PointEvaluation
{
  std::vector<std::vector<double>> distances;
  std::vector<std::array<double, 3>> nipple_error;
  std::vector<double> raw; ///< recording - model [m] (distances, then landmarks)
  std::vector<double> r;   ///< raw / noise sigma
};

class Evaluator
{
public:
  Evaluator(const Recording& rec, MPI_Comm comm) : _rec(rec), _comm(comm), _forward(postures(rec), comm)
  {
  }

  PointEvaluation operator()(const Config& c)
  {
    int rank;
    MPI_Comm_rank(_comm, &rank);
    const std::size_t np = _rec.postures.size();
    PointEvaluation e;
    e.distances.resize(np);
    auto visit = [&](std::size_t i, const Model& model)
    {
      const SkinSurface s = gather_skin_surface(model); // complete on rank 0
      std::vector<double> d(_rec.postures[i].points.size(), 0.0);
      if (rank == 0)
      {
        const auto m = match_points(s, _rec.postures[i].points);
        for (std::size_t k = 0; k < m.size(); ++k)
          d[k] = m[k].distance;
      }
      MPI_Bcast(d.data(), static_cast<int>(d.size()), MPI_DOUBLE, 0, _comm);
      e.distances[i] = std::move(d);
    };
    const auto obs = _forward.solve(c, visit);
    // Residuals "recording - model" [m]: the distances, then the landmarks.
    std::vector<double> raw;
    for (std::size_t i = 0; i < np; ++i)
      raw.insert(raw.end(), e.distances[i].begin(), e.distances[i].end());
    for (std::size_t i = 0; i < np; ++i)
      if (const auto& n = _rec.postures[i].nipple)
        for (int k = 0; k < 3; ++k)
          raw.push_back((*n)[k] - obs[i].nipple[k]);
    std::size_t j = 0;
    for (std::size_t i = 0; i < np; ++i)
      for (auto& d : e.distances[i])
        d = raw[j++];
    for (std::size_t i = 0; i < np; ++i)
    {
      std::array<double, 3> err = {nan, nan, nan};
      if (_rec.postures[i].nipple)
        for (int k = 0; k < 3; ++k)
          err[k] = -raw[j++]; // model - landmark
      e.nipple_error.push_back(err);
    }
    e.raw = raw;
    for (std::size_t k = 0; k < raw.size(); ++k)
      e.r.push_back(raw[k] / (_sigma.empty() ? _rec.noise_sigma : _sigma[k]));
    return e;
  }

  int posture_solves() const { return _forward.posture_solves(); }
  /// Skin surface documents of case `c` per posture (collective; rank 0).
  std::vector<nlohmann::json> surfaces(const Config& c) { return _forward.surfaces(c); }
  /// Standard deviation of each raw residual from now on [m] (default: the noise sigma).
  void set_sigma(std::vector<double> s) { _sigma = std::move(s); }

private:
  static std::vector<Posture> postures(const Recording& rec)
  {
    std::vector<Posture> p;
    for (const auto& q : rec.postures)
      p.push_back({q.name, q.theta_deg});
    return p;
  }
  const Recording& _rec;
  MPI_Comm _comm;
  ForwardModel _forward;
  std::vector<double> _sigma;
};

double normal_tail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

FitState make_state(const Config& c, const std::vector<Free>& frees,
                    const std::vector<double>& y, const Matrix& J, const PointEvaluation& e,
                    int evaluations)
{
  FitState s;
  s.config = c;
  s.distances = e.distances;
  s.nipple_error = e.nipple_error;
  s.r = e.r;
  s.J = J;
  s.evaluations = evaluations;
  for (double x : e.r)
    s.chi2 += x * x;
  s.dof = static_cast<int>(e.r.size()) - static_cast<int>(frees.size());
  s.gof_z = (s.chi2 - s.dof) / std::sqrt(2.0 * s.dof);
  s.gof_p = normal_tail(s.gof_z);
  for (std::size_t i = 0; i < frees.size(); ++i)
  {
    s.names.push_back(frees[i].name);
    s.units.push_back(frees[i].unit);
    s.values.push_back(std::exp(y[i]));
  }
  if (!frees.empty())
    s.uncertainty = gauss_newton_uncertainty(J, y, s.names,
                                             std::max(1.0, s.chi2 / std::max(s.dof, 1)));
  for (const auto& d : e.distances)
  {
    double ss = 0, mx = 0;
    for (double x : d)
    {
      ss += x * x;
      mx = std::max(mx, std::abs(x));
    }
    s.rms.push_back(std::sqrt(ss / std::max<std::size_t>(d.size(), 1)));
    s.max_abs.push_back(mx);
  }
  return s;
}

/// Fit `frees` of `base` from y0; the state at the optimum.
FitState fit(Evaluator& ev, const Config& base, const std::vector<Free>& frees,
             const std::vector<double>& y0, const LsqOptions& o, const std::string& label)
{
  if (frees.empty())
  {
    const PointEvaluation e = ev(base);
    return make_state(base, frees, {}, {}, e, 1);
  }
  std::vector<double> lo, hi;
  for (const auto& f : frees)
  {
    lo.push_back(std::log(f.lo));
    hi.push_back(std::log(f.hi));
  }
  auto f = [&](const std::vector<double>& y) { return ev(config_at(base, frees, y)).r; };
  auto progress = [&](int it, double chi2, const std::vector<double>& y)
  {
    std::string p;
    for (std::size_t i = 0; i < y.size(); ++i)
      p += fmt::format("{}{} = {:.4g}", i ? ", " : "", frees[i].name, std::exp(y[i]));
    log::info("{}: iteration {}, chi2 = {:.1f}, {}", label, it, chi2, p);
  };
  const LsqResult r = levenberg_marquardt(f, y0, lo, hi, o, progress);
  log::info("{}: {} ({} evaluations)", label, r.stop_reason, r.evaluations);
  const Config c = config_at(base, frees, r.y);
  const PointEvaluation e = ev(c);
  return make_state(c, frees, r.y, r.J, e, r.evaluations + 1);
}

std::vector<double> log_values(const FitState& s)
{
  std::vector<double> y;
  for (double v : s.values)
    y.push_back(std::log(v));
  return y;
}

/// Projected sensitivity P j with P = I - J (J^T J)^-1 J^T.
std::vector<double> project_out(const Matrix& J, const std::vector<double>& j)
{
  const std::size_t n = J.empty() ? 0 : J[0].size();
  if (n == 0)
    return j;
  Matrix A(n, std::vector<double>(n, 0.0));
  std::vector<double> b(n, 0.0), a;
  for (std::size_t i = 0; i < J.size(); ++i)
    for (std::size_t p = 0; p < n; ++p)
    {
      b[p] += J[i][p] * j[i];
      for (std::size_t q = 0; q < n; ++q)
        A[p][q] += J[i][p] * J[i][q];
    }
  if (!solve_dense(A, b, a))
    return j;
  std::vector<double> out = j;
  for (std::size_t i = 0; i < J.size(); ++i)
    for (std::size_t p = 0; p < n; ++p)
      out[i] -= J[i][p] * a[p];
  return out;
}

std::string where_text(const Point& c, const std::array<double, 3>& nipple, double R)
{
  const double dz = c[2] - nipple[2];
  std::string vertical = dz > 0.01 ? "upper pole" : (dz < -0.01 ? "lower pole" : "at nipple height");
  std::string depth = c[1] > 0.75 * nipple[1] ? "around the nipple-areola"
                      : (c[1] < 0.3 * nipple[1] ? "near the chest wall" : "mid-breast");
  std::string side = c[0] < 0.25 * R ? "close to the nipple's sagittal plane"
                                     : fmt::format("{:.0f} mm off the nipple's sagittal plane", 1e3 * c[0]);
  return fmt::format("{}, {}, {}", vertical, depth, side);
}

} // namespace

double boundary_lr_critical(double level)
{
  // 0.5 P(chi2_1 > x) = 0.5 erfc(sqrt(x / 2)) = level, by bisection.
  double lo = 0, hi = 200;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(std::sqrt(mid / 2)) > level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<Region> locate_regions(const Recording& rec, const FitState& f,
                                   const std::vector<double>& sigma,
                                   int neighbours, double region_z)
{
  std::vector<Region> regions;
  const double R = f.config.number("geometry.R");
  for (std::size_t p = 0; p < rec.postures.size(); ++p)
  {
    const auto& pts = rec.postures[p].points;
    const auto& d = f.distances[p];
    const std::size_t n = pts.size();
    const int k = std::min<int>(neighbours, static_cast<int>(n) - 1);
    // k nearest neighbours of each point (brute force).
    std::vector<std::vector<std::size_t>> knn(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      std::vector<std::pair<double, std::size_t>> dist;
      for (std::size_t j = 0; j < n; ++j)
        if (j != i)
        {
          double s = 0;
          for (int c = 0; c < 3; ++c)
            s += std::pow(pts[i][c] - pts[j][c], 2);
          dist.push_back({s, j});
        }
      std::partial_sort(dist.begin(), dist.begin() + k, dist.end());
      for (int m = 0; m < k; ++m)
        knn[i].push_back(dist[m].second);
    }
    // Neighbourhood z: sum of k + 1 whitened residuals / sqrt(k + 1) ~ N(0, 1) for noise.
    std::vector<double> z(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      double s = d[i] / sigma[p];
      for (auto j : knn[i])
        s += d[j] / sigma[p];
      z[i] = s / std::sqrt(k + 1.0);
    }
    // Clusters: same-sign flagged points connected through neighbourhoods.
    std::vector<int> label(n, -1);
    for (std::size_t seed = 0; seed < n; ++seed)
    {
      if (label[seed] >= 0 || std::abs(z[seed]) < region_z)
        continue;
      const double sign = z[seed] > 0 ? 1 : -1;
      std::vector<std::size_t> members;
      std::deque<std::size_t> queue = {seed};
      label[seed] = static_cast<int>(seed);
      while (!queue.empty())
      {
        const std::size_t i = queue.front();
        queue.pop_front();
        members.push_back(i);
        for (auto j : knn[i])
          if (label[j] < 0 && sign * z[j] >= region_z)
          {
            label[j] = static_cast<int>(seed);
            queue.push_back(j);
          }
      }
      if (members.size() < 3)
        continue;
      // The region: the flagged points and their neighbourhoods.
      std::vector<char> in(n, 0);
      for (auto i : members)
      {
        in[i] = 1;
        for (auto j : knn[i])
          in[j] = 1;
      }
      Region r;
      r.posture = rec.postures[p].name;
      double sum_r = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (in[i])
        {
          ++r.points;
          for (int c = 0; c < 3; ++c)
            r.centroid[c] += pts[i][c];
          r.mean_residual += d[i];
          r.max_residual = std::max(r.max_residual, std::abs(d[i]));
          sum_r += d[i] / sigma[p];
        }
      for (int c = 0; c < 3; ++c)
        r.centroid[c] /= r.points;
      r.mean_residual /= r.points;
      r.z = sum_r / std::sqrt(static_cast<double>(r.points));
      const auto& ne = f.nipple_error[p];
      std::array<double, 3> nipple = {0, 0, 0};
      // Model nipple = landmark + error; without a landmark, the most projected point.
      if (rec.postures[p].nipple && std::isfinite(ne[0]))
        for (int c = 0; c < 3; ++c)
          nipple[c] = (*rec.postures[p].nipple)[c] + ne[c];
      else
        nipple = *std::max_element(pts.begin(), pts.end(),
                                   [](const Point& a, const Point& b) { return a[1] < b[1]; });
      r.where = where_text(r.centroid, nipple, R);
      regions.push_back(r);
    }
  }
  std::sort(regions.begin(), regions.end(),
            [](const Region& a, const Region& b) { return std::abs(a.z) > std::abs(b.z); });
  return regions;
}

namespace
{
void check_options(const DiagnoseOptions& o)
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
  if (o.max_rounds < 1 || o.max_rounds > 10)
    throw InputError(fmt::format("--max-rounds = {} is out of range: allowed [1, 10]", o.max_rounds));
}

Config finer(const Config& c, double ratio)
{
  Config f = c;
  f.set("geometry.mesh_size", c.number("geometry.mesh_size") / ratio);
  f.validate();
  return f;
}

/// Numerical noise floor of the diagnosis mesh at the fitted state: the RMS
/// change e_h of each posture's distances (and of each landmark) on a mesh
/// `ratio` times finer; sigma_eff^2 = sigma^2 + e_h^2 per residual.
std::vector<double> noise_floor(Evaluator& ev, Evaluator& fine_ev, const Recording& rec,
                                const FitState& state, double ratio, Diagnosis& d)
{
  log::info("numerical noise floor: solving the fitted model on a mesh {:g} times finer", ratio);
  const PointEvaluation ef = fine_ev(finer(state.config, ratio));
  const PointEvaluation ec = ev(state.config);
  std::vector<double> sigma;
  std::size_t k = 0;
  for (std::size_t p = 0; p < rec.postures.size(); ++p)
  {
    double ss = 0;
    const std::size_t n = rec.postures[p].points.size();
    for (std::size_t i = 0; i < n; ++i, ++k)
      ss += std::pow(ef.raw[k] - ec.raw[k], 2);
    d.mesh_error[p] = std::sqrt(ss / n);
    d.sigma_eff[p] = std::hypot(rec.noise_sigma, d.mesh_error[p]);
    sigma.insert(sigma.end(), n, d.sigma_eff[p]);
    log::info("numerical noise floor of posture '{}': {:.3f} mm (sigma_eff {:.3f} mm)",
              rec.postures[p].name, 1e3 * d.mesh_error[p], 1e3 * d.sigma_eff[p]);
  }
  for (const auto& P : rec.postures)
    if (P.nipple)
    {
      double ss = 0;
      for (int c = 0; c < 3; ++c, ++k)
        ss += std::pow(ef.raw[k] - ec.raw[k], 2);
      sigma.insert(sigma.end(), 3, std::hypot(rec.noise_sigma, std::sqrt(ss / 3)));
    }
  return sigma;
}

/// Score statistic of candidate `c` at q = 0 (diagnose.hpp, step 3), with the
/// LR the mesh error `mesh_e` alone would give it (empty: none).
CandidateScore score(Evaluator& ev, const Candidate& c, const FitState& state,
                     const std::vector<double>& mesh_e, double kappa)
{
  CandidateScore s;
  s.name = c.name;
  const double probe = 0.05 * c.typical;
  try
  {
    const PointEvaluation e = ev(c.with(state.config, probe));
    std::vector<double> j(state.r.size());
    for (std::size_t i = 0; i < j.size(); ++i)
      j[i] = (e.r[i] - state.r[i]) / probe;
    const auto Pj = project_out(state.J, j);
    double U = 0, I = 0, Ue = 0;
    for (std::size_t i = 0; i < j.size(); ++i)
    {
      U -= Pj[i] * state.r[i];
      I += Pj[i] * Pj[i];
      if (!mesh_e.empty())
        Ue -= Pj[i] * mesh_e[i];
    }
    s.score = (U > 0 && I > 0) ? U * U / I : 0.0;
    s.p_value = I > 0 ? normal_tail(U / std::sqrt(I)) : 1.0;
    s.estimate = I > 0 ? U / I : 0.0;
    // Extrapolated to the error against the exact solution (Richardson,
    // order 1: kappa = 1/(1 - 1/r)).
    s.mesh_allowance = (Ue > 0 && I > 0) ? kappa * kappa * Ue * Ue / I : 0.0;
  }
  catch (const SolveError& err)
  {
    log::warn("candidate '{}': the probe solve failed ({}); not scored", c.name, err.what());
  }
  log::info("candidate '{}': score {:.1f} (one-sided p = {:.2g}), linearised {} = {:.3g} {}, "
            "mesh-error allowance {:.1f}",
            s.name, s.score, s.p_value, c.parameter, s.estimate, c.unit, s.mesh_allowance);
  return s;
}

/// Values and intervals of a found model on the finer mesh, with the
/// numerical part |ln p_h - ln p_{h/r}| / (r - 1) (Richardson, order 1)
/// added in quadrature to the statistical SE of ln p.
FitState with_numerical_uncertainty(const FitState& coarse, const FitState& fine, double ratio,
                                    std::vector<double>& se_numerical)
{
  FitState f = fine;
  f.config.set("geometry.mesh_size", coarse.config.number("geometry.mesh_size")); // the user's mesh
  auto& u = f.uncertainty;
  for (std::size_t i = 0; i < f.values.size() && i < u.se_log.size(); ++i)
  {
    const double se_num = std::abs(std::log(f.values[i] / coarse.values[i])) / (ratio - 1);
    se_numerical.push_back(se_num);
    u.se_log[i] = std::hypot(u.se_log[i], se_num);
    u.interval[i] = {f.values[i] * std::exp(-1.96 * u.se_log[i]),
                     f.values[i] * std::exp(1.96 * u.se_log[i])};
  }
  return f;
}
} // namespace

Diagnosis diagnose(const Recording& rec, const Config& current_in, const DiagnoseOptions& o,
                   MPI_Comm comm)
{
  const auto t0 = std::chrono::steady_clock::now();
  check_options(o);
  Config current = current_in;
  for (const auto& [k, v] : rec.known)
    current.set(k == "rho" ? "tissue.rho" : "geometry." + k, v);
  current.validate();

  Diagnosis d;
  d.noise_sigma = rec.noise_sigma;
  d.mesh_error.assign(rec.postures.size(), 0.0);
  d.sigma_eff.assign(rec.postures.size(), rec.noise_sigma);
  Evaluator ev(rec, comm);
  std::unique_ptr<Evaluator> fine_ev; // the finer mesh of the noise floor
  std::vector<Free> frees = frees_from_fit(o.fit, current);
  std::vector<double> y0;
  for (const auto& f : frees)
    y0.push_back(std::log(std::clamp(f.start, f.lo, f.hi)));

  // 1-2. Fit the current model; noise floor; fit again with sigma_eff.
  FitState state = fit(ev, current, frees, y0, o.lsq, "fit of the current model");
  if (o.mesh_ratio > 1)
  {
    fine_ev = std::make_unique<Evaluator>(rec, comm);
    const auto sigma = noise_floor(ev, *fine_ev, rec, state, o.mesh_ratio, d);
    ev.set_sigma(sigma);
    fine_ev->set_sigma(sigma);
    state = fit(ev, current, frees, log_values(state), o.lsq, "fit of the current model");
  }
  const double kappa = o.mesh_ratio > 1 ? 1.0 / (1.0 - 1.0 / o.mesh_ratio) : 0.0;

  for (int round = 0; round < o.max_rounds; ++round)
  {
    Round rd;
    rd.before = state;
    // 4. Where.
    rd.regions = locate_regions(rec, state, d.sigma_eff, o.neighbours, o.region_z);
    if (!o.discover)
    {
      d.fit_only = true;
      d.rounds.push_back(rd);
      break;
    }
    // 5. What: score every applicable candidate at its null value, with the
    // share of the mesh error e = r_h - r_{h/r} along its direction.
    std::vector<double> mesh_e;
    if (fine_ev)
    {
      const PointEvaluation ef = (*fine_ev)(finer(state.config, o.mesh_ratio));
      for (std::size_t i = 0; i < state.r.size(); ++i)
        mesh_e.push_back(state.r[i] - ef.r[i]);
    }
    std::size_t tested = 0;
    for (const auto& c : candidate_library())
      if (c.applicable(state.config)
          && (o.candidates.empty()
              || std::find(o.candidates.begin(), o.candidates.end(), c.name) != o.candidates.end()))
      {
        rd.scores.push_back(score(ev, c, state, mesh_e, kappa));
        ++tested;
      }
    std::sort(rd.scores.begin(), rd.scores.end(),
              [](const auto& a, const auto& b) { return a.score > b.score; });
    const double level = o.alpha / std::max<std::size_t>(tested, 1);
    rd.critical = boundary_lr_critical(level);
    // 6. Model it: refit the (at most o.refits) best-scoring significant
    // candidates; the largest margin over its critical value wins (the
    // score is a local, linearised ranking; the refit is not).
    std::vector<Free> trial;
    for (std::size_t k = 0; k < rd.scores.size() && k < static_cast<std::size_t>(o.refits); ++k)
    {
      const CandidateScore& sc = rd.scores[k];
      if (sc.p_value >= level)
        break;
      const Candidate& cand = candidate(sc.name);
      std::vector<Free> t = frees;
      t.push_back(free_candidate(cand));
      auto y = log_values(state);
      y.push_back(std::log(std::clamp(sc.estimate, cand.typical * 1e-3, cand.typical * 1e2)));
      FitState after;
      try
      {
        after = fit(ev, current, t, y, o.lsq, "refit with " + cand.name);
      }
      catch (const SolveError& err)
      {
        log::warn("candidate '{}': the refit failed ({}); skipped", cand.name, err.what());
        continue;
      }
      // 7. Accept: LR against the boundary-corrected critical value plus
      // the candidate's mesh-error allowance.
      const double lr = state.chi2 - after.chi2;
      const double critical = rd.critical + sc.mesh_allowance;
      log::info("candidate '{}': LR = {:.1f} against the critical {:.1f} (level {:.2g}, mesh-error "
                "allowance {:.1f})",
                cand.name, lr, critical, level, sc.mesh_allowance);
      rd.refits.push_back({cand.name, lr});
      if (rd.tested.empty() || lr - critical > rd.lr - rd.critical_used)
      {
        rd.tested = cand.name;
        rd.lr = lr;
        rd.critical_used = critical;
        rd.after = std::move(after);
        trial = t;
      }
    }
    rd.accepted = !rd.tested.empty() && rd.lr > rd.critical_used;
    if (!rd.tested.empty())
      log::info("best refit '{}': LR = {:.1f}: {}", rd.tested, rd.lr,
                rd.accepted ? "accepted" : "rejected");
    d.rounds.push_back(rd);
    if (!rd.accepted)
      break; // 8. nothing (more) is significant
    d.discovered.push_back(rd.tested);
    frees = trial;
    current = rd.after.config; // the candidate term is on from now on
    state = rd.after;
  }
  d.final_fit = state;
  // 9. Numerical uncertainty of the found values.
  if (fine_ev && (!d.discovered.empty() || d.fit_only) && !frees.empty())
  {
    const FitState f = fit(*fine_ev, finer(current, o.mesh_ratio), frees, log_values(state),
                           o.lsq, "refit on the finer mesh");
    d.final_fit = with_numerical_uncertainty(state, f, o.mesh_ratio, d.se_numerical);
  }
  d.surfaces = ev.surfaces(d.final_fit.config);
  if (fine_ev)
    d.posture_solves += fine_ev->posture_solves();
  d.posture_solves += ev.posture_solves();
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  d.verdict = verdict_text(d, rec, o.alpha);
  return d;
}
} // namespace breastsim::calibration
