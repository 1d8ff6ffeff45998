// SPDX-License-Identifier: LGPL-3.0-or-later
#include "upload_summaries.hpp"
#include "fit_parameters.hpp"
#include "result_summary.hpp"
#include <array>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
nlohmann::json read_json(const fs::path& file) { return read_result_json(file); }

/// The flag of the fit in words, or its relative standard error (first
/// order in ln p: SE(ln p) = SE(p) / p).
std::string identifiability(const nlohmann::json& p)
{
  return identifiability_in_words(p.value("flag", ""), p.value("se_log", nlohmann::json()));
}
} // namespace

nlohmann::json summarize_recording_fit(const Config& start, const fs::path& dir)
{
  const auto d = read_json(dir / "diagnosis.json");
  const auto& fit = d.at("final");
  nlohmann::json params = nlohmann::json::array(), fitted = nlohmann::json::object();
  for (const auto& p : fit.at("parameters"))
  {
    const std::string key = calibration::fit_alias(p.at("name").get<std::string>()).key;
    params.push_back({{"name", p.at("name")}, {"key", key}, {"unit", p.at("unit")},
                      {"initial", start.number(key)}, {"fitted", p.at("value")},
                      {"interval_95", p.value("interval95", nlohmann::json::array({nullptr, nullptr}))},
                      {"at_bound", false}, {"identifiability", identifiability(p)}});
    fitted[key] = p.at("value");
  }
  auto postures = nlohmann::json::array();
  for (const auto& q : fit.at("postures"))
    postures.push_back({{"posture", q.at("name")}, {"rms_mm", q.at("rms_mm")}, {"max_mm", q.at("max_mm")}});
  return {{"kind", "calibrate"},
          {"data", "recording"},
          {"parameters", params},
          {"fitted_overrides", fitted},
          {"chi2_before", nullptr},
          {"chi2_after", fit.at("chi2")},
          {"measurements", fit.at("dof").get<long>() + static_cast<long>(params.size())},
          {"evaluations", fit.at("evaluations")},
          {"stop_reason", d.value("verdict", "")},
          {"noise_sigma_mm", d.at("noise_sigma_mm")},
          {"postures", postures},
          {"warnings", nlohmann::json::array()}};
}

nlohmann::json summarize_scan(const Config& c, const fs::path& folder)
{
  auto j = summarize_result("simulate", c, folder / "result");
  j["kind"] = "scan";
  for (auto& p : j["postures"])
  {
    // A full breast's surface is not mirrored: its volume in front of the chest is the whole.
    const fs::path surface = folder / "result" / ("surface_" + p["posture"].get<std::string>() + ".json");
    if (p["pre"].contains("volume_front_cm3") && !read_json(surface).value("mirror_x", true))
      p["pre"]["volume_front_cm3"] = p["pre"]["volume_front_cm3"].get<double>() / 2;
  }
  const auto m = read_json(folder / "model" / "summary.json");
  const auto nipple = m.at("nipple_m").get<std::array<double, 3>>();
  j["scan"] = {{"posture", m.at("posture")},
               {"points", m.at("scan_points")},
               {"triangles", m.at("scan_triangles")},
               {"fit_rms_mm", 1e3 * m.at("fit_rms_m").get<double>()},
               {"noise_rms_mm", 1e3 * m.at("noise_rms_m").get<double>()},
               {"nipple_mm", {1e3 * nipple[0], 1e3 * nipple[1], 1e3 * nipple[2]}},
               {"footprint_radius_mm", 1e3 * m.at("footprint_radius_m").get<double>()},
               {"tetrahedra", m.at("tetrahedra")},
               {"volume_cm3", 1e6 * m.at("volume_m3").get<double>()}};
  const auto n = read_json(folder / "neutral" / "summary.json");
  const auto& its = n.at("iterations");
  j["neutral"] = {{"converged", n.value("converged", false)},
                  {"iterations", its.size()},
                  {"mismatch_rms_mm", its.empty() ? 0.0 : 1e3 * its.back().at("mismatch_rms_m").get<double>()}};
  return j;
}

std::map<std::string, std::string> scan_files()
{
  return {{"scan_model_summary.json", "model/summary.json"},
          {"scan_frame.json", "model/frame.json"},
          {"neutral_summary.json", "neutral/summary.json"},
          {"neutral_case.toml", "neutral/case.reference.toml"}};
}
} // namespace breastsim::app
