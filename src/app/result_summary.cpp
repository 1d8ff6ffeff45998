// SPDX-License-Identifier: LGPL-3.0-or-later
#include "result_summary.hpp"
#include "fit_parameters.hpp"
#include "output_target.hpp"
#include <array>
#include <cmath>
#include <fstream>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
nlohmann::json read_json(const fs::path& file) { return read_result_json(file); }

/// One posture's observables in mm, with the nipple's distance to the base.
nlohmann::json posture_view(const nlohmann::json& p, const fs::path& surface)
{
  const auto nipple = p.at("nipple_m").get<std::array<double, 3>>();
  nlohmann::json v = {{"nipple_mm", {1e3 * nipple[0], 1e3 * nipple[1], 1e3 * nipple[2]}},
                      {"nipple_to_base_mm", 1e3 * nipple[1]},
                      {"projection_mm", 1e3 * p.at("projection_m").get<double>()},
                      {"z_min_mm", 1e3 * p.at("z_min_m").get<double>()},
                      {"z_max_mm", 1e3 * p.at("z_max_m").get<double>()},
                      {"volume_cm3", 1e6 * p.at("volume_m3").get<double>()}};
  if (fs::exists(surface))
  {
    const auto doc = read_json(surface);
    const auto pole = pole_volumes(doc, nipple[2]);
    v["lower_pole_share"] = lower_pole_share(doc, nipple[2]);
    v["volume_front_cm3"] = 2e6 * pole.total; // full breast, in front of the chest wall y = 0
  }
  return v;
}

nlohmann::json ideals()
{
  return {{"nipple_to_base_mm", 1e3 * ideal_nipple_to_base}, {"lower_pole_share", ideal_lower_pole_share}};
}

nlohmann::json summarize_surgery(const Config& c, const fs::path& dir, const nlohmann::json& s)
{
  const double resected = s.at("resected_volume_m3").get<double>();
  const double rho = c.number(calibration::fit_alias("rho").key); // the density's key, from the forms
  nlohmann::json j = {{"kind", "surgery"},
                      {"resected_volume_cm3", 1e6 * resected},
                      {"resected_volume_mesh_cm3", 1e6 * s.at("resected_volume_mesh_m3").get<double>()},
                      {"resected_weight_g", 1e3 * resected * rho},
                      {"tissue_rho_kg_m3", rho},
                      {"volume_pre_cm3", 1e6 * s.at("volume_pre_m3").get<double>()},
                      {"volume_post_cm3", 1e6 * s.at("volume_remaining_m3").get<double>()},
                      {"max_suture_gap_mm", 1e3 * s.at("suture").at("max_gap_m").get<double>()},
                      {"incision", s.at("incision")},
                      {"ideal", ideals()},
                      {"postures", nlohmann::json::array()}};
  if (s.value("model", "") == "full breast") // a scanned breast: both sutures' gaps
  {
    j["model"] = "full breast";
    j["max_gap_keel_mm"] = 1e3 * s.at("suture").at("max_gap_keel_m").get<double>();
    j["max_gap_chest_mm"] = 1e3 * s.at("suture").at("max_gap_chest_m").get<double>();
  }
  const auto &pre = s.at("preop"), &post = s.at("postop");
  for (std::size_t i = 0; i < pre.size() && i < post.size(); ++i)
  {
    const std::string name = pre[i].at("posture");
    j["postures"].push_back(
        {{"posture", name}, {"theta_deg", pre[i].at("theta_deg")},
         {"pre", posture_view(pre[i], dir / "preop" / ("surface_" + name + ".json"))},
         {"post", posture_view(post[i], dir / "postop" / ("surface_" + name + ".json"))}});
  }
  return j;
}

/// The identifiability of a fitted parameter of report.json in words.
std::string identifiability(const nlohmann::json& p)
{
  return identifiability_in_words(p.value("flag", ""), p.value("relative_standard_error", nlohmann::json()));
}

nlohmann::json summarize_calibration(const fs::path& dir)
{
  const auto rep = read_json(dir / "report.json");
  nlohmann::json params = nlohmann::json::array(), fitted = nlohmann::json::object();
  for (const auto& p : rep.at("fit"))
  {
    params.push_back({{"name", p.at("name")}, {"key", p.at("key")}, {"unit", p.at("unit")},
                      {"initial", p.at("initial")}, {"fitted", p.at("fitted")},
                      {"interval_95", p.at("interval_95")}, {"at_bound", p.value("at_bound", false)},
                      {"identifiability", identifiability(p)}});
    fitted[p.at("key").get<std::string>()] = p.at("fitted");
  }
  const auto& m = rep.at("misfit");
  return {{"kind", "calibrate"},
          {"parameters", params},
          {"fitted_overrides", fitted},
          {"chi2_before", m.at("chi2_before")},
          {"chi2_after", m.at("chi2_after")},
          {"measurements", m.at("measurements")},
          {"evaluations", rep.value("evaluations", 0)},
          {"stop_reason", rep.value("stop_reason", "")},
          {"warnings", rep.value("warnings", nlohmann::json::array())}};
}

/// The rows of a sweep (sweep.json) in the app's units, the varied keys in the
/// order of the request.
nlohmann::json summarize_sweep(const Config& c, const fs::path& dir)
{
  const double rho = c.number(calibration::fit_alias("rho").key);
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& r : read_json(dir / "sweep.json"))
  {
    // The combination's folder, named as sweep() names it (key=value joined by _).
    std::string folder;
    for (const auto& [key, value] : r.at("parameters").items())
      folder += (folder.empty() ? "" : "_") + key + "=" + plain_text(Value(value.get<double>()));
    nlohmann::json row = {{"parameters", r.at("parameters")}, {"ok", r.at("ok")},
                          {"postop_surface", folder + "_postop_surface_standing.json"}};
    if (!r.at("ok").get<bool>())
    {
      row["error"] = r.value("error", "");
      rows.push_back(row);
      continue;
    }
    const double v = r.at("resected_volume_m3"), gap = r.at("max_suture_gap_m");
    const auto n = r.at("nipple_standing_m").get<std::array<double, 3>>();
    row.update({{"resected_volume_cm3", 1e6 * v}, {"resected_weight_g", 1e3 * v * rho},
                {"nipple_mm", {1e3 * n[0], 1e3 * n[1], 1e3 * n[2]}}, {"nipple_to_base_mm", 1e3 * n[1]},
                {"projection_mm", 1e3 * r.at("projection_standing_m").get<double>()},
                {"z_min_mm", 1e3 * r.at("z_min_standing_m").get<double>()},
                {"lower_pole_share", r.at("lower_pole_share")}, {"max_suture_gap_mm", 1e3 * gap},
                {"wall_time_s", r.at("wall_time_s")}});
    rows.push_back(row);
  }
  return {{"kind", "sweep"}, {"ideal", ideals()}, {"rows", rows}};
}

nlohmann::json summarize_simulation(const fs::path& dir, const nlohmann::json& s)
{
  nlohmann::json j = {{"kind", "simulate"}, {"ideal", ideals()}, {"postures", nlohmann::json::array()}};
  for (const auto& p : s.at("postures"))
  {
    const std::string name = p.at("posture");
    j["postures"].push_back({{"posture", name}, {"theta_deg", p.at("theta_deg")},
                             {"pre", posture_view(p, dir / ("surface_" + name + ".json"))}});
  }
  return j;
}
} // namespace

nlohmann::json read_result_json(const fs::path& file)
{
  std::ifstream f(file);
  return nlohmann::json::parse(f);
}

std::string identifiability_in_words(const std::string& flag, const nlohmann::json& relative_se)
{
  if (!flag.empty())
    return flag;
  return relative_se.is_number()
             ? "identifiable: relative standard error " +
                   std::to_string(static_cast<int>(std::lround(100 * relative_se.get<double>()))) + " %"
             : "identifiable";
}

nlohmann::json summarize_result(const std::string& kind, const Config& c, const fs::path& dir)
{
  if (kind == "calibrate")
    return summarize_calibration(dir);
  if (kind == "sweep")
    return summarize_sweep(c, dir);
  if (kind == "patient")
    return {{"kind", "patient"}, {"patient_model", read_json(dir / "patient_model.json")}};
  if (kind == "plan")
    return {{"kind", "plan"}, {"patient_model", read_json(dir / "patient_model.json")},
            {"plan", read_json(dir / "plan.json")}};
  const auto s = read_json(dir / "summary.json");
  return kind == "surgery" ? summarize_surgery(c, dir, s) : summarize_simulation(dir, s);
}

std::map<std::string, std::string> result_files(const fs::path& job_folder)
{
  std::map<std::string, std::string> files = {{"log.txt", "log.txt"}};
  const auto marker = read_marker(job_folder / "result");
  for (const auto& f : marker.value("files", nlohmann::json::array()))
  {
    const fs::path rel = f.get<std::string>();
    const auto ext = rel.extension().string();
    if (ext != ".json" && ext != ".toml" && ext != ".html" && ext != ".png" && ext != ".txt" && ext != ".csv")
      continue;
    std::string name = rel.generic_string();
    for (auto& ch : name)
      if (ch == '/')
        ch = '_';
    files[name] = (fs::path("result") / rel).generic_string();
  }
  return files;
}
} // namespace breastsim::app
