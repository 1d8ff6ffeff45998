// SPDX-License-Identifier: LGPL-3.0-or-later
#include "measurements.hpp"
#include "json_file.hpp"
#include "errors.hpp"
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

namespace breastsim::calibration
{
namespace
{
/// Lengths above this are almost certainly millimetres, not metres.
constexpr double max_length = 1.0;
/// Default measurement error when the file gives none [m].
constexpr double default_sigma = 1e-3;

struct MeasurementReader
{
  std::string source;

  [[noreturn]] void fail(const std::string& key, const std::string& what) const
  {
    throw InputError(fmt::format("measurements '{}': key '{}' {}", source, key, what));
  }

  double number(const nlohmann::json& v, const std::string& key) const
  {
    if (!v.is_number())
      fail(key, fmt::format("= {} is not a number", v.dump()));
    const double x = v.get<double>();
    if (!std::isfinite(x))
      fail(key, fmt::format("= {} is not a finite number", x));
    if (std::abs(x) > max_length)
      fail(key, fmt::format("= {} m is out of range: |value| <= {} m (SI units: metres, not mm)",
                            x, max_length));
    return x;
  }

  double sigma(const nlohmann::json& v, const std::string& key) const
  {
    const double s = number(v, key);
    if (!(s > 0))
      fail(key, fmt::format("= {} is out of range: the measurement error sigma must be > 0 m", s));
    return s;
  }

  /// A value given as `x` or `{"value": x, "sigma": s}`.
  std::pair<nlohmann::json, double> value_and_sigma(const nlohmann::json& v, const std::string& key,
                                                    double sigma_default) const
  {
    if (!v.is_object())
      return {v, sigma_default};
    for (const auto& [k, _] : v.items())
      if (k != "value" && k != "sigma")
        fail(key + "." + k, "is not allowed (allowed: value, sigma)");
    if (!v.contains("value"))
      fail(key + ".value", "is missing");
    return {v.at("value"), v.contains("sigma") ? sigma(v.at("sigma"), key + ".sigma") : sigma_default};
  }
};

const std::map<std::string, Quantity>& scalar_quantities()
{
  static const std::map<std::string, Quantity> q = {{"projection", Quantity::projection},
                                                    {"z_min", Quantity::z_min},
                                                    {"z_max", Quantity::z_max},
                                                    {"height", Quantity::height},
                                                    {"base_perimeter", Quantity::base_perimeter}};
  return q;
}

bool must_be_positive(Quantity q)
{
  return q == Quantity::projection || q == Quantity::height || q == Quantity::base_perimeter;
}

void add_scalar(const MeasurementReader& rd, Measurements& m, std::size_t posture, Quantity q,
                const nlohmann::json& v, const std::string& key, double sigma_default)
{
  auto [x, s] = rd.value_and_sigma(v, key, sigma_default);
  const double value = rd.number(x, key);
  if (must_be_positive(q) && !(value > 0))
    rd.fail(key, fmt::format("= {} is out of range: a {} must be > 0 m", value, quantity_name(q)));
  m.items.push_back({posture, q, value, s, key});
}

std::size_t posture_index(Measurements& m, const Posture& p)
{
  for (std::size_t i = 0; i < m.postures.size(); ++i)
    if (m.postures[i].theta_deg == p.theta_deg)
      return i;
  m.postures.push_back(p);
  return m.postures.size() - 1;
}

/// The nipple [x, y, z] of posture `posture` as three measurements.
void add_nipple(const MeasurementReader& rd, Measurements& m, std::size_t posture, const nlohmann::json& v,
                const std::string& key, const std::string& prefix, double sigma_default)
{
  auto [x, s] = rd.value_and_sigma(v, key, sigma_default);
  if (!x.is_array() || x.size() != 3)
    rd.fail(key, fmt::format("= {} must be a list [x, y, z] in metres", x.dump()));
  const Quantity xyz[3] = {Quantity::nipple_x, Quantity::nipple_y, Quantity::nipple_z};
  for (int d = 0; d < 3; ++d)
  {
    const std::string k = prefix + quantity_name(xyz[d]);
    m.items.push_back({posture, xyz[d], rd.number(x[d], k), s, k});
  }
}

/// The posture of entry `at` (its name or theta_deg).
Posture posture_of(const MeasurementReader& rd, const nlohmann::json& p, const std::string& at)
{
  if (!p.is_object())
    rd.fail(at, "must be an object with 'name' or 'theta_deg' and measured values");
  if (p.contains("name") == p.contains("theta_deg"))
    rd.fail(at, "must have exactly one of 'name' (standing, supine, all_fours, prone) or "
                "'theta_deg'");
  if (p.contains("name"))
  {
    if (!p.at("name").is_string())
      rd.fail(at + ".name", fmt::format("= {} is not a string", p.at("name").dump()));
    return named_posture(p.at("name").get<std::string>());
  }
  if (!p.at("theta_deg").is_number() || !std::isfinite(p.at("theta_deg").get<double>()))
    rd.fail(at + ".theta_deg", fmt::format("= {} is not a finite number", p.at("theta_deg").dump()));
  return posture_from_angle(p.at("theta_deg").get<double>());
}

/// One entry of "postures" with its measured values.
void add_posture(const MeasurementReader& rd, Measurements& m, const nlohmann::json& p, const std::string& at,
                 double sigma0, std::set<double>& seen)
{
  const Posture posture = posture_of(rd, p, at);
  if (!seen.insert(posture.theta_deg).second)
    rd.fail(at, fmt::format("repeats the posture theta = {:g} deg", posture.theta_deg));
  const std::size_t pi = posture_index(m, posture);
  const std::string prefix = posture.name + ".";
  const double sigma_p = p.contains("sigma") ? rd.sigma(p.at("sigma"), at + ".sigma") : sigma0;
  const std::size_t before = m.items.size();
  for (const auto& [k, v] : p.items())
  {
    if (k == "name" || k == "theta_deg" || k == "sigma")
      continue;
    if (auto q = scalar_quantities().find(k); q != scalar_quantities().end())
      add_scalar(rd, m, pi, q->second, v, prefix + k, sigma_p);
    else if (k == "nipple")
      add_nipple(rd, m, pi, v, prefix + k, prefix, sigma_p);
    else
      rd.fail(at + "." + k, "is not allowed (allowed: name, theta_deg, sigma, projection, "
                            "z_min, z_max, height, nipple, base_perimeter)");
  }
  if (m.items.size() == before)
    rd.fail(at, fmt::format("(posture '{}') has no measured value", posture.name));
}

/// The top-level keys, units and the postures list; the default sigma.
double check_document(const MeasurementReader& rd, const nlohmann::json& doc)
{
  if (!doc.is_object())
    throw InputError(fmt::format("measurements '{}': expected a JSON object", rd.source));
  static const std::set<std::string> top_keys
      = {"units", "sigma", "postures", "base_perimeter", "breast_height", "comment", "written_by"};
  for (const auto& [k, _] : doc.items())
    if (!top_keys.count(k))
      rd.fail(k, "is not allowed (allowed: units, sigma, postures, base_perimeter, "
                 "breast_height, comment, written_by)");
  if (!doc.contains("units"))
    rd.fail("units", "is missing: it must be \"SI\" (lengths in metres)");
  if (doc.at("units") != "SI")
    rd.fail("units", fmt::format("= {} is not allowed: it must be \"SI\" (lengths in metres)",
                                 doc.at("units").dump()));
  const double sigma0 = doc.contains("sigma") ? rd.sigma(doc.at("sigma"), "sigma") : default_sigma;
  if (!doc.contains("postures"))
    rd.fail("postures", "is missing: give a list of postures with their measurements");
  const auto& ps = doc.at("postures");
  if (!ps.is_array() || ps.empty())
    rd.fail("postures", "must be a non-empty list of postures");
  return sigma0;
}
} // namespace

std::string quantity_name(Quantity q)
{
  switch (q)
  {
  case Quantity::projection: return "projection";
  case Quantity::z_min: return "z_min";
  case Quantity::z_max: return "z_max";
  case Quantity::height: return "height";
  case Quantity::nipple_x: return "nipple_x";
  case Quantity::nipple_y: return "nipple_y";
  case Quantity::nipple_z: return "nipple_z";
  case Quantity::base_perimeter: return "base_perimeter";
  }
  return "?";
}

Measurements parse_measurements(const nlohmann::json& doc, const std::string& source)
{
  const MeasurementReader rd{source};
  const double sigma0 = check_document(rd, doc);
  const auto& ps = doc.at("postures");
  Measurements m;
  std::set<double> seen;
  for (std::size_t i = 0; i < ps.size(); ++i)
    add_posture(rd, m, ps[i], fmt::format("postures[{}]", i), sigma0, seen);
  // Consulting-room shorthands, measured standing.
  const std::pair<const char*, Quantity> standing_keys[]
      = {{"base_perimeter", Quantity::base_perimeter}, {"breast_height", Quantity::height}};
  for (const auto& [k, q] : standing_keys)
    if (doc.contains(k))
      add_scalar(rd, m, posture_index(m, named_posture("standing")), q, doc.at(k), k, sigma0);
  return m;
}

Measurements read_measurements(const std::filesystem::path& file)
{
  return parse_measurements(read_json_file(file, "measurements file"), file.string());
}
} // namespace breastsim::calibration
