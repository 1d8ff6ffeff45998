// SPDX-License-Identifier: LGPL-3.0-or-later
#include "recording.hpp"
#include "json_file.hpp"
#include "errors.hpp"
#include <cmath>
#include <fmt/format.h>
#include <set>

namespace breastsim::calibration
{
namespace
{
constexpr double max_coordinate = 1.0; ///< |coordinate| above this is not metres

struct RecordingReader
{
  std::string source;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const
  {
    throw InputError(fmt::format("recording '{}': key '{}' {}", source, key, what));
  }

  double number(const nlohmann::json& v, const std::string& key, double lo, double hi,
                const std::string& unit) const
  {
    if (!v.is_number())
      fail(key, fmt::format("= {} is not a number", v.dump()));
    const double x = v.get<double>();
    if (!std::isfinite(x))
      fail(key, fmt::format("= {} is not a finite number", x));
    if (x < lo || x > hi)
      fail(key, fmt::format("= {} {} is out of range: allowed [{}, {}] {}", x, unit, lo, hi, unit));
    return x;
  }

  Point point(const nlohmann::json& v, const std::string& key) const
  {
    if (!v.is_array() || v.size() != 3)
      fail(key, fmt::format("= {} must be [x, y, z] in metres", v.dump().substr(0, 80)));
    Point p;
    for (int c = 0; c < 3; ++c)
      p[c] = number(v[c], fmt::format("{}[{}]", key, c), -max_coordinate, max_coordinate,
                    "m (SI units: metres, not mm)");
    return p;
  }

  const nlohmann::json& require(const nlohmann::json& obj, const std::string& name,
                                const std::string& prefix) const
  {
    if (!obj.contains(name))
      fail(prefix + name, "is missing");
    return obj.at(name);
  }

  void only(const nlohmann::json& obj, const std::set<std::string>& allowed,
            const std::string& prefix) const
  {
    for (const auto& [k, _] : obj.items())
      if (!allowed.count(k))
      {
        std::string list;
        for (const auto& a : allowed)
          list += (list.empty() ? "" : ", ") + a;
        fail(prefix + k, fmt::format("is not allowed (allowed: {})", list));
      }
  }
};
} // namespace

Recording parse_recording(const nlohmann::json& j, const std::string& source)
{
  const RecordingReader rd{source};
  if (!j.is_object())
    rd.fail("(top level)", "must be a JSON object");
  rd.only(j, {"format", "noise_sigma", "known", "postures", "truth", "units", "comment", "written_by"}, "");
  const auto& format = rd.require(j, "format", "");
  if (format != recording_format)
    rd.fail("format", fmt::format("= {} is not supported (expected \"{}\")", format.dump(),
                                  recording_format));
  if (j.contains("units") && j.at("units") != "m")
    rd.fail("units", fmt::format("= {} is not allowed: recordings are in metres (\"m\")",
                                 j.at("units").dump()));
  Recording r;
  r.source = source;
  r.noise_sigma = rd.number(rd.require(j, "noise_sigma", ""), "noise_sigma", 1e-7, 0.02, "m");
  if (j.contains("known"))
  {
    const auto& k = j.at("known");
    if (!k.is_object())
      rd.fail("known", "must be an object like {\"R\": 0.07, \"H\": 0.06, \"rho\": 970}");
    rd.only(k, {"R", "H", "rho"}, "known.");
    if (k.contains("R"))
      r.known["R"] = rd.number(k.at("R"), "known.R", 0.02, 0.2, "m");
    if (k.contains("H"))
      r.known["H"] = rd.number(k.at("H"), "known.H", 0.01, 0.2, "m");
    if (k.contains("rho"))
      r.known["rho"] = rd.number(k.at("rho"), "known.rho", 500, 2000, "kg/m^3");
  }
  const auto& ps = rd.require(j, "postures", "");
  if (!ps.is_array() || ps.empty())
    rd.fail("postures", "must be a non-empty list of postures");
  std::set<std::string> names;
  for (std::size_t i = 0; i < ps.size(); ++i)
  {
    const std::string pre = fmt::format("postures[{}].", i);
    const auto& p = ps[i];
    if (!p.is_object())
      rd.fail(pre.substr(0, pre.size() - 1), "must be an object");
    rd.only(p, {"name", "theta_deg", "points", "landmarks"}, pre);
    RecordedPosture q;
    const auto& name = rd.require(p, "name", pre);
    if (!name.is_string() || name.get<std::string>().empty())
      rd.fail(pre + "name", "must be a non-empty string");
    q.name = name.get<std::string>();
    if (!names.insert(q.name).second)
      rd.fail(pre + "name", fmt::format("= \"{}\" appears twice", q.name));
    q.theta_deg = rd.number(rd.require(p, "theta_deg", pre), pre + "theta_deg", -180, 180, "deg");
    const auto& pts = rd.require(p, "points", pre);
    if (!pts.is_array() || pts.size() < 10)
      rd.fail(pre + "points", fmt::format("must be a list of at least 10 points [x, y, z] (has {})",
                                          pts.is_array() ? pts.size() : 0));
    if (pts.size() > max_recorded_points)
      rd.fail(pre + "points", fmt::format("holds {} points: allowed at most {} per posture (as "
                                          "`breastsim record --points`)",
                                          pts.size(), max_recorded_points));
    for (std::size_t k = 0; k < pts.size(); ++k)
    {
      const Point x = rd.point(pts[k], fmt::format("{}points[{}]", pre, k));
      // Half breast: x >= 0 up to a few noise levels.
      if (x[0] < -5 * r.noise_sigma)
        rd.fail(fmt::format("{}points[{}][0]", pre, k),
                fmt::format("= {} m is out of range: the recording holds the half breast x >= 0 "
                            "(allowed x >= -5 noise_sigma = {} m)", x[0], -5 * r.noise_sigma));
      q.points.push_back(x);
    }
    if (p.contains("landmarks"))
    {
      const auto& l = p.at("landmarks");
      if (!l.is_object())
        rd.fail(pre + "landmarks", "must be an object like {\"nipple\": [x, y, z]}");
      rd.only(l, {"nipple"}, pre + "landmarks.");
      if (l.contains("nipple"))
        q.nipple = rd.point(l.at("nipple"), pre + "landmarks.nipple");
    }
    r.postures.push_back(std::move(q));
  }
  if (j.contains("truth"))
    r.truth = j.at("truth");
  return r;
}

Recording read_recording(const std::filesystem::path& file)
{
  return parse_recording(read_json_file(file, "recording"), file.string());
}

bool is_recording(const nlohmann::json& doc)
{
  return doc.is_object() && doc.contains("format") && doc.at("format") == recording_format;
}

nlohmann::json to_json(const Recording& r)
{
  nlohmann::json j;
  j["format"] = recording_format;
  j["units"] = "m";
  j["noise_sigma"] = r.noise_sigma;
  if (!r.known.empty())
    j["known"] = r.known;
  j["postures"] = nlohmann::json::array();
  for (const auto& p : r.postures)
  {
    nlohmann::json q = {{"name", p.name}, {"theta_deg", p.theta_deg}, {"points", p.points}};
    if (p.nipple)
      q["landmarks"]["nipple"] = *p.nipple;
    j["postures"].push_back(q);
  }
  if (!r.truth.is_null())
    j["truth"] = r.truth;
  return j;
}
} // namespace breastsim::calibration
