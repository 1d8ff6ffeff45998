// SPDX-License-Identifier: LGPL-3.0-or-later
#include "plan_search.hpp"
#include "errors.hpp"
#include "log.hpp"
#include "on_root.hpp"
#include "pole_volumes.hpp"
#include "surgery.hpp"
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <nlopt.hpp>

namespace breastsim::clinic
{
double plan_objective(const PlanOutcome& o, const PlanTargets& t)
{
  if (!o.ok)
    return 1e6;
  auto sq = [](double v, double target, double tol) { return std::pow((v - target) / tol, 2); };
  double f = 0;
  if (t.sn_n)
    f += sq(o.sn_n, *t.sn_n, t.length_tolerance);
  if (t.n_imf)
    f += sq(o.n_imf, *t.n_imf, t.length_tolerance);
  if (t.grams)
    f += sq(o.terms.resection_grams, *t.grams, t.grams_tolerance * *t.grams);
  if (t.lower_pole)
    f += sq(o.lower_pole, *t.lower_pole, t.share_tolerance);
  return f;
}

std::vector<std::string> unmet_targets(const PlanOutcome& o, const PlanTargets& t)
{
  std::vector<std::string> u;
  if (!o.ok)
    return {"no incision could be operated: " + o.error};
  auto cm = [&](const char* name, double v, const std::optional<double>& target)
  {
    if (target && std::abs(v - *target) > t.length_tolerance)
      u.push_back(fmt::format("{}: target {:.1f} cm, closest {:.1f} cm", name, 100 * *target, 100 * v));
  };
  cm("post-operative SN-N", o.sn_n, t.sn_n);
  cm("post-operative N-IMF", o.n_imf, t.n_imf);
  if (t.grams && std::abs(o.terms.resection_grams - *t.grams) > t.grams_tolerance * *t.grams)
    u.push_back(fmt::format("resection: target {:.0f} g, closest {:.0f} g", *t.grams, o.terms.resection_grams));
  if (t.lower_pole && std::abs(o.lower_pole - *t.lower_pole) > t.share_tolerance)
    u.push_back(fmt::format("lower pole: target {:.0f} %, closest {:.0f} %", 100 * *t.lower_pole, 100 * o.lower_pole));
  return u;
}

PlanOutcome evaluate_plan(const SideModel& m, const IncisionSpec& in, const Config& c,
                          const std::filesystem::path& dir, MPI_Comm comm)
{
  PlanOutcome o;
  o.incision = in;
  try
  {
    Config k = c;
    k.set("incision.a_deg", in.a_deg);
    k.set("incision.s", in.s);
    k.set("incision.h", in.h);
    k.set("incision.d", in.d);
    k.validate();
    const SurgeryResult r = surgery(k, OutputTarget::claim(dir.string(), {}, comm), comm);
    const auto& post = r.post.front(); // standing is the first posture (checked by plan_side)
    o.nipple = post.observables.nipple;
    o.volume_post = r.volume_remaining;
    std::vector<double> v(5, 0.0);
    on_root(comm,
            [&]
            {
              std::ifstream pre_file(dir / "preop" / "surface_standing.json"), post_file(dir / "postop" / "surface_standing.json");
              const auto pre_doc = nlohmann::json::parse(pre_file), post_doc = nlohmann::json::parse(post_file);
              const SkinSurface pre = skin_surface(pre_doc), after = skin_surface(post_doc);
              v[0] = taut_tape(after, m.notch, o.nipple);
              v[1] = nipple_to_fold(after, o.nipple);
              v[2] = lower_pole_share(post_doc, o.nipple[2]);
              const SurgicalTerms st = surgical_terms(HalfCapSpec::from(k), in, pre, m.notch, k.number("tissue.rho"),
                                                      MPI_COMM_SELF);
              v[3] = st.new_nipple_sn_n;
              v[4] = st.vertical_limb;
            });
    MPI_Bcast(v.data(), 5, MPI_DOUBLE, 0, comm);
    o.sn_n = v[0], o.n_imf = v[1], o.lower_pole = v[2];
    o.terms = {v[3], v[4], 1e3 * k.number("tissue.rho") * r.resected_volume};
    o.ok = true;
  }
  catch (const InputError& e)
  {
    o.error = e.what();
  }
  catch (const SolveError& e)
  {
    o.error = e.what();
  }
  return o;
}

namespace
{
/// The searched box: s in [0, 0.8 R], h in [0.1 H, 0.95 H] (A above the
/// old nipple's level, D between the chest and the apex), and the new
/// fold's depth d in [0, 0.85 R], as unit coordinates.
struct SearchBox
{
  double R, H;
  IncisionSpec at(const std::array<double, 3>& u, const IncisionSpec& base) const
  {
    IncisionSpec in = base;
    in.s = 0.8 * R * u[0];
    in.h = H * (0.1 + 0.85 * u[1]);
    in.d = 0.85 * R * u[2];
    return in;
  }
  double unit_depth(double d) const { return std::clamp(d / (0.85 * R), 0.0, 1.0); }
};

class Search
{
public:
  Search(const SideModel& m, const PlanTargets& t, const Config& c, std::filesystem::path dir, MPI_Comm comm)
      : _m(m), _t(t), _c(c), _dir(std::move(dir)), _comm(comm),
        _box{c.number("geometry.R"), c.number("geometry.H")}, _base(IncisionSpec::from(c))
  {
  }

  double operator()(const std::array<double, 3>& u)
  {
    IncisionSpec in = _box.at(u, _base);
    PlanOutcome o;
    try
    {
      if (_t.grams) // the keel's angle carries the weight
        in.a_deg = angle_for_grams(HalfCapSpec::from(_c), in, *_t.grams, _c.number("tissue.rho"));
      o = evaluate_plan(_m, in, _c, _dir, _comm);
    }
    catch (const InputError& e)
    {
      o.incision = in;
      o.error = e.what();
    }
    o.objective = plan_objective(o, _t);
    log::info("plan {}: s = {:.1f} mm, h = {:.1f} mm, a = {:.1f} deg: {}", _m.side, 1e3 * in.s, 1e3 * in.h,
              in.a_deg, o.ok ? fmt::format("objective {:.3g}", o.objective) : "not operable");
    _all.push_back(o);
    return o.objective;
  }

  std::vector<PlanOutcome> _all;

private:
  const SideModel& _m;
  const PlanTargets& _t;
  Config _c;
  std::filesystem::path _dir;
  MPI_Comm _comm;
  SearchBox _box;
  IncisionSpec _base;
};
} // namespace

std::vector<std::string> trade_offs(const std::vector<PlanOutcome>& searched, const PlanTargets& t)
{
  struct Goal
  {
    const char* name;
    std::optional<double> target;
    std::function<double(const PlanOutcome&)> value;
    double scale;
    const char* unit;
  };
  const std::vector<Goal> goals = {
      {"post-operative SN-N", t.sn_n, [](const PlanOutcome& o) { return o.sn_n; }, 100, "cm"},
      {"post-operative N-IMF", t.n_imf, [](const PlanOutcome& o) { return o.n_imf; }, 100, "cm"},
      {"lower pole", t.lower_pole, [](const PlanOutcome& o) { return o.lower_pole; }, 100, "%"}};
  std::vector<std::string> out;
  for (const auto& g : goals)
  {
    if (!g.target)
      continue;
    const PlanOutcome* best = nullptr;
    for (const auto& o : searched)
      if (o.ok && (!best || std::abs(g.value(o) - *g.target) < std::abs(g.value(*best) - *g.target)))
        best = &o;
    if (!best)
      continue;
    std::string others;
    for (const auto& h : goals)
      if (h.target && h.name != g.name)
        others += fmt::format(", {} {:.1f} {}", h.name, h.scale * h.value(*best), h.unit);
    out.push_back(fmt::format("{} alone comes to {:.1f} {} (target {:.1f}) with the new nipple marked {:.1f} cm from "
                              "the notch and a vertical limb of {:.1f} cm{}",
                              g.name, g.scale * g.value(*best), g.unit, g.scale * *g.target,
                              100 * best->terms.new_nipple_sn_n, 100 * best->terms.vertical_limb, others));
  }
  return out;
}

namespace
{
/// NLopt's Nelder-Mead on the first `n` unit coordinates from `start` (the
/// fold's depth held at `ud` when n = 2), at most `evals` surgeries; stops
/// when every target is within half its tolerance. Returns the best
/// objective and leaves its point in `start`.
double nelder_mead(Search& search, std::array<double, 3>& start, unsigned n, int evals, double ud)
{
  std::pair<Search*, double> context{&search, ud};
  nlopt::opt opt(nlopt::LN_NELDERMEAD, n);
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_initial_step(0.1);
  opt.set_maxeval(evals);
  opt.set_stopval(0.25);
  opt.set_xtol_abs(1e-3);
  opt.set_min_objective(
      [](const std::vector<double>& x, std::vector<double>&, void* data)
      {
        auto* c = static_cast<std::pair<Search*, double>*>(data);
        return (*c->first)({x[0], x[1], x.size() > 2 ? x[2] : c->second});
      },
      &context);
  std::vector<double> x(start.begin(), start.begin() + n);
  double f = std::numeric_limits<double>::infinity();
  try
  {
    opt.optimize(x, f);
  }
  catch (const nlopt::roundoff_limited&)
  {
  }
  // The best point seen (NLopt's x is its last best, equal to it).
  for (unsigned k = 0; k < n; ++k)
    start[k] = x[k];
  return f;
}
} // namespace

namespace
{
/// Why no searched incision removes `grams`: the range of weights over all
/// of them, and where the most is removed; nothing if one could.
std::optional<std::string> weight_out_of_reach(const std::vector<PlanOutcome>& searched, const Config& c, double grams)
{
  const HalfCapSpec cap = HalfCapSpec::from(c);
  std::optional<WeightRange> all;
  IncisionSpec heaviest;
  for (const auto& o : searched)
  {
    try
    {
      const WeightRange w = weight_range(cap, o.incision, c.number("tissue.rho"));
      if (w.least <= grams && grams <= w.most)
        return std::nullopt;
      if (!all || w.most > all->most)
        heaviest = o.incision;
      all = all ? WeightRange{std::min(all->least, w.least), std::max(all->most, w.most), 0, 0} : w;
    }
    catch (const InputError&)
    {
    }
  }
  if (!all)
    return std::nullopt;
  return fmt::format("a resection of {:.0f} g is out of reach for this breast: the {} incisions searched remove "
                     "from {:.0f} g to {:.0f} g (the most with the new nipple at s = {:.1f} mm, D at h = {:.1f} mm, "
                     "the fold at d = {:.1f} mm)",
                     grams, searched.size(), all->least, all->most, 1e3 * heaviest.s, 1e3 * heaviest.h,
                     1e3 * heaviest.d);
}
} // namespace

SidePlan plan_side(const SideModel& m, const PlanTargets& t, const std::filesystem::path& scratch,
                   const std::filesystem::path& final_dir, MPI_Comm comm)
{
  if (t.incision) // the surgeon's own incision: no search
  {
    SidePlan p{m.side, t, evaluate_plan(m, *t.incision, m.config, final_dir, comm), {}, {}, {}};
    p.best.objective = plan_objective(p.best, t);
    p.searched = {p.best};
    p.unmet = unmet_targets(p.best, t);
    return p;
  }
  Config search_case = m.config;
  search_case.set("postures.names", std::vector<std::string>{"standing"});
  search_case.set("postures.theta_deg", std::vector<double>{});
  Search search(m, t, search_case, scratch, comm);
  // A 4 x 4 grid in (s, h) at the case's fold depth.
  const double ud = SearchBox{m.config.number("geometry.R"), 0}.unit_depth(IncisionSpec::from(m.config).d);
  std::array<double, 3> best{0.5, 0.5, ud};
  double best_f = std::numeric_limits<double>::infinity();
  for (double us : {0.125, 0.375, 0.625, 0.875})
    for (double uh : {0.125, 0.375, 0.625, 0.875})
      if (const double f = search({us, uh, ud}); f < best_f)
        best_f = f, best = {us, uh, ud};
  // Nelder-Mead in (s, h) from the grid's best point; then, when two or
  // more targets besides the weight are still missed, in (s, h, d) from there.
  if (best_f > 1.0 && best_f < 1e6)
    best_f = nelder_mead(search, best, 2, 16, ud);
  const int free_targets = t.sn_n.has_value() + t.n_imf.has_value() + t.lower_pole.has_value();
  if (free_targets >= 2 && best_f > 1.0 && best_f < 1e6)
    nelder_mead(search, best, 3, 16, ud);
  SidePlan p;
  p.side = m.side;
  p.targets = t;
  p.searched = search._all;
  const auto it = std::min_element(p.searched.begin(), p.searched.end(),
                                   [](const PlanOutcome& a, const PlanOutcome& b) { return a.objective < b.objective; });
  if (!it->ok) // nothing operable: the first refusal says why, the weight's by the whole search's range
  {
    p.best = *it;
    if (t.grams)
      if (const auto why = weight_out_of_reach(p.searched, m.config, *t.grams))
        p.best.error = *why;
    p.unmet = unmet_targets(p.best, t);
    return p;
  }
  // The chosen plan with every posture of the case (standing first).
  PlanOutcome chosen = evaluate_plan(m, it->incision, m.config, final_dir, comm);
  chosen.objective = plan_objective(chosen, t);
  p.best = chosen;
  p.unmet = unmet_targets(chosen, t);
  if (!p.unmet.empty() && (t.sn_n.has_value() + t.n_imf.has_value() + t.lower_pole.has_value() + t.grams.has_value()) > 1)
    p.trade_offs = trade_offs(p.searched, t);
  return p;
}

nlohmann::json to_json(const SidePlan& p)
{
  auto outcome = [](const PlanOutcome& o)
  {
    nlohmann::json j = {{"incision", {{"a_deg", o.incision.a_deg}, {"s_m", o.incision.s}, {"h_m", o.incision.h},
                                      {"d_m", o.incision.d}}},
                        {"ok", o.ok}};
    if (!o.ok)
    {
      j["error"] = o.error;
      return j;
    }
    j.update({{"surgical", {{"new_nipple_sn_n_mm", 1e3 * o.terms.new_nipple_sn_n},
                            {"vertical_limb_mm", 1e3 * o.terms.vertical_limb},
                            {"resection_g", o.terms.resection_grams}}},
              {"post_standing", {{"sn_n_mm", 1e3 * o.sn_n}, {"n_imf_mm", 1e3 * o.n_imf},
                                 {"lower_pole_share", o.lower_pole}, {"nipple_m", o.nipple}}},
              {"volume_post_cm3", 1e6 * o.volume_post},
              {"objective", o.objective}});
    return j;
  };
  nlohmann::json targets = nlohmann::json::object();
  if (p.targets.sn_n)
    targets["sn_n_mm"] = 1e3 * *p.targets.sn_n;
  if (p.targets.n_imf)
    targets["n_imf_mm"] = 1e3 * *p.targets.n_imf;
  if (p.targets.grams)
    targets["resection_g"] = *p.targets.grams;
  if (p.targets.lower_pole)
    targets["lower_pole_share"] = *p.targets.lower_pole;
  nlohmann::json searched = nlohmann::json::array();
  for (const auto& o : p.searched)
    searched.push_back(outcome(o));
  return {{"side", p.side}, {"targets", targets}, {"plan", outcome(p.best)}, {"met", p.unmet.empty()},
          {"unmet", p.unmet}, {"trade_offs", p.trade_offs}, {"searched", searched}};
}
} // namespace breastsim::clinic
