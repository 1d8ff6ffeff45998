// SPDX-License-Identifier: LGPL-3.0-or-later
#include "landmarks.hpp"
#include "errors.hpp"
#include "json_file.hpp"
#include "strings.hpp"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace breastsim::clinic
{
const std::vector<LandmarkRange>& landmark_ranges()
{
  static const std::vector<LandmarkRange> r = {
      {"sn_n", 0.15, 0.45, "breasts seen for reduction: about 19-21 cm is youthful, 45 cm is beyond the longest reported"},
      {"n_imf", 0.03, 0.25, "3 cm is a minimal lower pole, 25 cm beyond the largest ptotic breasts"},
      {"base_width", 0.08, 0.25, "the breast's footprint on the chest"},
      {"nipple_midline", 0.06, 0.20, "the nipple lies lateral of the sternum, medial of the axilla"},
      {"projection", 0.02, 0.20, "the nipple's distance in front of the chest wall"},
  };
  return r;
}

const LandmarkRange* violated_range(const std::string& key, double value)
{
  for (const auto& r : landmark_ranges())
    if (r.key == key && !(value >= r.lo && value <= r.hi))
      return &r;
  return nullptr;
}

namespace
{
const std::vector<std::string> side_keys = {"sn_n", "n_imf", "base_width", "nipple_midline", "projection",
                                            "ptosis_grade", "scan"};
const std::vector<std::string> scan_keys = {"file", "units", "nipple", "notch", "up", "lateral"};

struct Reader
{
  std::string source;
  double unit = 0; // metres per file unit
  std::string unit_name;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const
  {
    throw InputError(fmt::format("patient '{}': key '{}' {}", source, key, what));
  }

  /// Refuse a key of object `j` that is not in `keys`, named `prefix` + key,
  /// with the closest allowed key and the list `allowed`.
  void only_keys(const nlohmann::json& j, const std::string& prefix, const std::vector<std::string>& keys,
                 const std::string& refusal, const std::string& allowed) const
  {
    for (const auto& [k, _] : j.items())
      if (std::find(keys.begin(), keys.end(), k) == keys.end())
      {
        const std::string guess = closest_match(k, keys);
        fail(prefix + k, refusal + (guess.empty() ? "" : " (did you mean '" + guess + "'?)") + "; allowed: " + allowed);
      }
  }

  double length(const nlohmann::json& side, const std::string& name, const std::string& key) const
  {
    const auto& v = side.at(name);
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      fail(key, fmt::format("= {} is not a finite number", shorten(v.dump())));
    const double x = v.get<double>() * unit;
    if (const LandmarkRange* r = violated_range(name, x))
      fail(key, fmt::format("= {} {} is out of range: [{}, {}] {} ({})", v.get<double>(), unit_name,
                            r->lo / unit, r->hi / unit, unit_name, r->why));
    return x;
  }

  std::array<double, 3> vector(const nlohmann::json& j, const std::string& key, double scale) const
  {
    const auto& v = j.at(key.substr(key.rfind('.') + 1));
    if (!v.is_array() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](const auto& x)
                                                        { return x.is_number() && std::isfinite(x.template get<double>()); }))
      fail(key, fmt::format("= {} must be three finite numbers [x, y, z] in the scanner's frame", shorten(v.dump())));
    return {scale * v[0].get<double>(), scale * v[1].get<double>(), scale * v[2].get<double>()};
  }

  SideScan scan(const nlohmann::json& j, const std::string& name) const
  {
    if (!j.is_object())
      fail(name, "must be an object: file, units, and optionally nipple, notch, up, lateral");
    only_keys(j, name + ".", scan_keys, "is not allowed", "file, units, nipple, notch, up, lateral");
    if (!j.contains("file") || !j.at("file").is_string() || j.at("file").get<std::string>().empty())
      fail(name + ".file", "must name the scan file (STL, PLY or OBJ; relative to the patient file's folder)");
    const std::string u = j.contains("units") && j.at("units").is_string() ? j.at("units").get<std::string>() : "";
    if (u != "mm" && u != "m")
      fail(name + ".units", "must be mm or m (the unit of the scan's coordinates)");
    SideScan s;
    s.file = j.at("file").get<std::string>();
    s.units = u == "mm" ? scan::Units::mm : scan::Units::m;
    const double k = u == "mm" ? 1e-3 : 1.0;
    if (j.contains("nipple"))
      s.nipple = vector(j, name + ".nipple", k);
    if (j.contains("notch"))
      s.notch = vector(j, name + ".notch", k);
    if (j.contains("up"))
      s.up = vector(j, name + ".up", 1.0);
    if (j.contains("lateral"))
      s.lateral = vector(j, name + ".lateral", 1.0);
    return s;
  }

  void optional_landmarks(const nlohmann::json& j, SideLandmarks& s, const std::string& name) const
  {
    if (j.contains("projection"))
      s.projection = length(j, "projection", name + ".projection");
    if (j.contains("ptosis_grade"))
    {
      const auto& g = j.at("ptosis_grade");
      if (!g.is_number_integer() || g.get<int>() < 0 || g.get<int>() > 3)
        fail(name + ".ptosis_grade", fmt::format("= {} is out of range: an integer 0-3 (Regnault: 0 none, "
                                                 "1 nipple at the fold, 2 1-3 cm below it, 3 more)",
                                                 shorten(g.dump())));
      s.ptosis_grade = g.get<int>();
    }
  }

  /// A side given as a scan: what the scan measures must not be entered too.
  void scanned_side(const nlohmann::json& j, const std::string& name, const SideScan& sc, SideLandmarks& s) const
  {
    for (const char* k : {"n_imf", "base_width", "projection", "ptosis_grade"})
      if (j.contains(k))
        fail(name + "." + k, "is measured on the scan: leave it out (or enter the landmarks without the scan)");
    for (const char* k : {"sn_n", "nipple_midline"})
      if (sc.notch && j.contains(k))
        fail(name + "." + k, "is measured on the scan from its notch: leave it out (or the notch)");
      else if (!sc.notch && !j.contains(k))
        fail(name + "." + k, "is missing: a scan without a notch needs sn_n and nipple_midline entered");
    if (!sc.notch)
    {
      s.sn_n = length(j, "sn_n", name + ".sn_n");
      s.nipple_midline = length(j, "nipple_midline", name + ".nipple_midline");
    }
  }

  SideLandmarks side(const nlohmann::json& j, const std::string& name, std::optional<SideScan>& sc) const
  {
    if (!j.is_object())
      fail(name, "must be an object of landmarks");
    only_keys(j, name + ".", side_keys, "is not a landmark",
              "sn_n, n_imf, base_width, nipple_midline, projection, ptosis_grade, scan");
    SideLandmarks s;
    if (j.contains("scan"))
    {
      sc = scan(j.at("scan"), name + ".scan");
      scanned_side(j, name, *sc, s);
      return s;
    }
    for (const char* k : {"sn_n", "n_imf", "base_width", "nipple_midline"})
      if (!j.contains(k))
        fail(name + "." + k, "is missing (required: sn_n, n_imf, base_width, nipple_midline; or a scan)");
    s.sn_n = length(j, "sn_n", name + ".sn_n");
    s.n_imf = length(j, "n_imf", name + ".n_imf");
    s.base_width = length(j, "base_width", name + ".base_width");
    s.nipple_midline = length(j, "nipple_midline", name + ".nipple_midline");
    optional_landmarks(j, s, name);
    if (s.nipple_midline < s.base_width / 2)
      fail(name + ".nipple_midline",
           fmt::format("= {} {} is less than half the base width ({} {}): the breast's base would cross "
                       "the midline",
                       s.nipple_midline / unit, unit_name, s.base_width / 2 / unit, unit_name));
    return s;
  }

  Body body(const nlohmann::json& j) const
  {
    const std::vector<std::string> keys = {"height", "weight_kg", "bra_size"};
    if (!j.is_object())
      fail("body", "must be an object (height, weight_kg, bra_size)");
    only_keys(j, "body.", keys, "is not allowed", "height (in the file's unit), weight_kg, bra_size");
    Body b;
    auto number = [&](const std::string& k, double scale, double lo, double hi, const std::string& unit)
    {
      const auto& v = j.at(k);
      if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() * scale >= lo) ||
          !(v.get<double>() * scale <= hi))
        fail("body." + k, fmt::format("= {} {} is out of range: [{}, {}] {} (adults)", shorten(v.dump()), unit,
                                      lo / scale, hi / scale, unit));
      return v.get<double>() * scale;
    };
    if (j.contains("height"))
      b.height = number("height", unit, 1.2, 2.2, unit_name);
    if (j.contains("weight_kg"))
      b.weight_kg = number("weight_kg", 1.0, 30, 250, "kg");
    if (j.contains("bra_size"))
    {
      if (!j.at("bra_size").is_string() || j.at("bra_size").get<std::string>().size() > 16)
        fail("body.bra_size", "must be a text of at most 16 characters (e.g. \"36DD\" or \"80E\")");
      b.bra_size = j.at("bra_size").get<std::string>();
    }
    return b;
  }
};
} // namespace

std::optional<double> Body::surface_area() const
{
  if (!height || !weight_kg)
    return std::nullopt;
  return std::sqrt(100 * *height * *weight_kg / 3600); // Mosteller
}

nlohmann::json to_json(const Body& b)
{
  nlohmann::json j = nlohmann::json::object();
  if (b.height)
    j["height_m"] = *b.height;
  if (b.weight_kg)
    j["weight_kg"] = *b.weight_kg;
  if (!b.bra_size.empty())
    j["bra_size"] = b.bra_size;
  if (const auto a = b.surface_area())
    j["bsa_m2"] = *a;
  return j;
}

Patient patient_from_json(const nlohmann::json& j, const std::string& source)
{
  Reader rd{source, 0, ""};
  if (!j.is_object())
    rd.fail("(document)", "must be a JSON object");
  rd.only_keys(j, "", {"format", "id", "units", "left", "right", "body"}, "is not allowed",
               "format, id, units, left, right, body");
  if (j.value("format", "") != "breastsim-patient/1")
    rd.fail("format", "must be \"breastsim-patient/1\"");
  const std::map<std::string, double> units = {{"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}};
  const auto u = j.contains("units") && j.at("units").is_string() ? j.at("units").get<std::string>() : "";
  if (!units.count(u))
    rd.fail("units", "must be one of mm, cm, m (the unit of every length in the file)");
  rd.unit = units.at(u);
  rd.unit_name = u;
  Patient p;
  if (j.contains("id"))
  {
    if (!j.at("id").is_string() || j.at("id").get<std::string>().size() > 64)
      rd.fail("id", "must be a text of at most 64 characters");
    p.id = j.at("id").get<std::string>();
  }
  for (const char* side : {"left", "right"})
    if (j.contains(side))
    {
      std::optional<SideScan> sc;
      p.sides[side] = rd.side(j.at(side), side, sc);
      if (sc)
        p.scans[side] = *sc;
    }
  if (p.sides.empty())
    rd.fail("left", "is missing: give the landmarks (or a scan) of the left and/or the right breast");
  if (j.contains("body"))
    p.body = rd.body(j.at("body"));
  return p;
}

Patient read_patient(const std::filesystem::path& file)
{
  Patient p = patient_from_json(calibration::read_json_file(file, "patient file"), file.string());
  for (auto& [_, sc] : p.scans)
    if (sc.file.is_relative())
      sc.file = file.parent_path() / sc.file;
  return p;
}

nlohmann::json to_json(const SideLandmarks& s)
{
  nlohmann::json j = {{"sn_n_mm", 1e3 * s.sn_n}, {"n_imf_mm", 1e3 * s.n_imf},
                      {"base_width_mm", 1e3 * s.base_width}, {"nipple_midline_mm", 1e3 * s.nipple_midline}};
  if (s.projection)
    j["projection_mm"] = 1e3 * *s.projection;
  if (s.ptosis_grade)
    j["ptosis_grade"] = *s.ptosis_grade;
  return j;
}
} // namespace breastsim::clinic
