// SPDX-License-Identifier: LGPL-3.0-or-later
#include "sweep.hpp"
#include "model_setup.hpp"
#include "neutral_mesh.hpp"
#include "case_groups.hpp"
#include "errors.hpp"
#include "on_root.hpp"
#include "log.hpp"
#include "output.hpp"
#include "pole_volumes.hpp"
#include "timer.hpp"
#include <fmt/format.h>
#include <fstream>

namespace breastsim
{
std::string sweep_key(const std::string& name)
{
  static const std::map<std::string, std::string> keys
      = {{"a", "incision.a_deg"}, {"s", "incision.s"}, {"h", "incision.h"}, {"d", "incision.d"}};
  if (auto it = keys.find(name); it != keys.end())
    return it->second;
  const KeyInfo& k = key_info(name); // throws for an unknown key
  if (k.type != KeyType::number && k.type != KeyType::integer && k.type != KeyType::boolean)
    throw InputError(fmt::format("sweep --vary {}: key '{}' is a {}; only number, integer and "
                                 "boolean keys can be varied (set it with --set instead)",
                                 name, k.key, type_name(k.type)));
  return name;
}

std::vector<Value> sweep_values(const Config& base, const std::string& key, const std::string& list)
{
  std::vector<Value> values;
  std::size_t begin = 0;
  while (begin <= list.size())
  {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    const std::string item = list.substr(begin, comma - begin);
    if (item.empty())
      throw InputError(fmt::format("sweep --vary {}={}: empty value in the list", key, list));
    Config probe = base;
    probe.set_text(key, item); // parsed and type-checked as the key's type
    values.push_back(probe.values().at(key));
    begin = comma + 1;
  }
  return values;
}

namespace
{
SweepRow run_one(Config c, const std::map<std::string, Value>& values, const std::filesystem::path& dir,
                 MPI_Comm comm, const Progress& progress)
{
  SweepRow row;
  row.parameters = values;
  Stopwatch clock("sweep: one incision");
  try
  {
    for (const auto& [k, v] : values)
      c.set(k, v);
    c.validate();
    auto r = surgery(c, OutputTarget::claim(dir.string(), {}, comm), comm, progress);
    auto it = std::find_if(r.post.begin(), r.post.end(),
                           [](const PostureResult& p) { return p.posture.theta_deg == 0.0; });
    const auto& o = it->observables;
    row.ok = true;
    row.resected_volume = r.resected_volume;
    row.nipple = o.nipple;
    row.projection = o.projection;
    row.z_min = o.z_min;
    std::ifstream surface(dir / "postop" / ("surface_" + it->posture.name + ".json")); // just written
    row.lower_pole_share = lower_pole_share(nlohmann::json::parse(surface), o.nipple[2]);
    row.max_gap = r.suture.max_gap;
    row.newton_iterations = r.suture.closure.newton_iterations;
    for (const auto& p : r.post)
      row.newton_iterations += p.path.newton_iterations;
    row.pre = std::move(r.pre);
    row.post = std::move(r.post);
  }
  catch (const InputError& e)
  {
    row.error = e.what();
  }
  catch (const SolveError& e)
  {
    row.error = e.what();
  }
  row.seconds = clock.seconds();
  return row;
}

nlohmann::json to_json(const SweepRow& r)
{
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [k, v] : r.parameters)
    std::visit([&](const auto& x) { params[k] = x; }, v);
  nlohmann::json j = {{"parameters", params}, {"ok", r.ok}, {"wall_time_s", r.seconds}};
  if (!r.ok || r.error.size())
  {
    j["error"] = r.error;
    return j;
  }
  j.update({{"resected_volume_m3", r.resected_volume}, {"nipple_standing_m", r.nipple},
            {"projection_standing_m", r.projection}, {"z_min_standing_m", r.z_min},
            {"lower_pole_share", r.lower_pole_share}, {"max_suture_gap_m", r.max_gap},
            {"newton_iterations", r.newton_iterations}});
  return j;
}

/// A row from its JSON (to_json), the parameters typed by their keys.
SweepRow row_from_json(const nlohmann::json& j)
{
  SweepRow r;
  for (const auto& [k, v] : j.at("parameters").items())
    switch (key_info(k).type)
    {
    case KeyType::integer: r.parameters[k] = v.get<std::int64_t>(); break;
    case KeyType::boolean: r.parameters[k] = v.get<bool>(); break;
    default: r.parameters[k] = v.get<double>();
    }
  r.ok = j.at("ok").get<bool>();
  r.seconds = j.at("wall_time_s").get<double>();
  if (!r.ok)
  {
    r.error = j.at("error").get<std::string>();
    return r;
  }
  r.resected_volume = j.at("resected_volume_m3").get<double>();
  r.nipple = j.at("nipple_standing_m").get<std::array<double, 3>>();
  r.projection = j.at("projection_standing_m").get<double>();
  r.z_min = j.at("z_min_standing_m").get<double>();
  r.lower_pole_share = j.at("lower_pole_share").get<double>();
  r.max_gap = j.at("max_suture_gap_m").get<double>();
  r.newton_iterations = j.at("newton_iterations").get<int>();
  return r;
}

std::string csv_table(const std::vector<SweepRow>& rows)
{
  std::string csv;
  for (const auto& [k, v] : rows.front().parameters)
    csv += k + ",";
  csv += "ok,resected_volume_cm3,nipple_y_mm,nipple_z_mm,projection_mm,z_min_mm,lower_pole_share,"
         "max_gap_mm,newton_iterations,wall_time_s\n";
  for (const auto& r : rows)
  {
    for (const auto& [k, v] : r.parameters)
      csv += plain_text(v) + ",";
    csv += fmt::format("{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.4f},{:.5f},{},{:.2f}\n", r.ok ? 1 : 0,
                       1e6 * r.resected_volume, 1e3 * r.nipple[1], 1e3 * r.nipple[2], 1e3 * r.projection,
                       1e3 * r.z_min, r.lower_pole_share, 1e3 * r.max_gap, r.newton_iterations, r.seconds);
  }
  return csv;
}

/// Every combination of the grid: its values and folder label.
std::vector<std::pair<std::map<std::string, Value>, std::string>> combinations(const SweepGrid& grid)
{
  std::vector<std::pair<std::map<std::string, Value>, std::string>> out;
  std::vector<std::size_t> idx(grid.size(), 0);
  while (true)
  {
    std::map<std::string, Value> values;
    std::string label;
    for (std::size_t i = 0; i < grid.size(); ++i)
    {
      values[grid[i].first] = grid[i].second[idx[i]];
      label += fmt::format("{}{}={}", label.empty() ? "" : "_", grid[i].first,
                           plain_text(grid[i].second[idx[i]]));
    }
    out.emplace_back(std::move(values), std::move(label));
    std::size_t i = 0;
    while (i < grid.size() && ++idx[i] == grid[i].second.size())
      idx[i++] = 0;
    if (i == grid.size())
      return out;
  }
}

/// Each combination solved by its group of ranks; the rows on rank 0 of the
/// whole communicator (with the Newton records of the rows its own group
/// solved), all rows on every rank when there is one group.
std::vector<SweepRow> run_all(const Config& base, const SweepGrid& grid, const std::filesystem::path& dir,
                              const CaseGroups& groups, const Progress& progress)
{
  const auto combos = combinations(grid);
  std::vector<SweepRow> mine(combos.size());
  std::vector<std::string> texts(combos.size());
  std::size_t share = 0, done = 0; // this group's combinations, those begun
  for (std::size_t i = 0; i < combos.size(); ++i)
    share += groups.runs(i) ? 1 : 0;
  for (std::size_t i = 0; i < combos.size(); ++i)
    if (groups.runs(i))
    {
      log::info("sweep: {} (group {} of {})", combos[i].second, groups.group() + 1, groups.groups());
      const double n = static_cast<double>(share), k = static_cast<double>(done++);
      const auto part = progress.part(k / n, (k + 1) / n, fmt::format("{} ({} of {}): ", combos[i].second, done, share));
      mine[i] = run_one(base, combos[i].first, dir / combos[i].second, groups.comm(), part);
      if (rank_of(groups.comm()) == 0)
        texts[i] = to_json(mine[i]).dump();
    }
  if (groups.groups() == 1)
    return mine;
  const std::vector<std::string> all = groups.gather(texts, combos.size());
  std::vector<SweepRow> rows;
  for (std::size_t i = 0; i < all.size(); ++i)
    rows.push_back(groups.runs(i) ? std::move(mine[i]) : row_from_json(nlohmann::json::parse(all[i])));
  return rows;
}
} // namespace

void check_sweep_request(const Config& base, const SweepGrid& grid)
{
  if (grid.empty())
    throw InputError("sweep: give at least one --vary name=v1,v2,...");
  for (const auto& [k, vs] : grid)
    if (vs.empty())
      throw InputError(fmt::format("sweep: --vary {} has no values", k));
  const auto postures = requested_postures(base);
  if (std::none_of(postures.begin(), postures.end(), [](const Posture& p) { return p.theta_deg == 0.0; }))
    throw InputError("key 'postures.names': the sweep reports the standing breast, so the postures "
                     "must include standing (theta = 0)");
}

std::vector<SweepRow> sweep(const Config& base, const SweepGrid& grid, const OutputTarget& out,
                            MPI_Comm comm, int ranks_per_case, const Progress& progress)
{
  check_sweep_request(base, grid);
  HalfCapSpec::from(base).require_parametric_cap("sweep (the incision cuts the cap)");
  const CaseGroups groups(comm, ranks_per_case, "--ranks-per-case");
  OutputDir dir(out, comm);
  const std::vector<SweepRow> rows = run_all(base, grid, dir.path(), groups, progress);
  // The table files (written by rank 0, which holds every row).
  nlohmann::json j = nlohmann::json::array();
  std::string csv;
  if (!rows.empty())
  {
    for (const auto& r : rows)
      j.push_back(to_json(r));
    csv = csv_table(rows);
  }
  write_json(dir.path() / "sweep.json", j, comm);
  write_text(dir.path() / "sweep.csv", csv, comm);
  write_text(dir.path() / "sweep.txt", rows.empty() ? std::string() : sweep_table(rows), comm);
  dir.commit();
  return rows;
}

std::string sweep_label(const SweepRow& row)
{
  std::string s;
  for (const auto& [k, v] : row.parameters)
    s += (s.empty() ? "" : ", ") + k + "=" + plain_text(v);
  return s;
}

std::string sweep_table(const std::vector<SweepRow>& rows)
{
  std::string s;
  for (const auto& [k, v] : rows.front().parameters)
    s += fmt::format("{:>16} ", k);
  s += fmt::format("{:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>9} {:>7} {:>7}\n", "resect", "nipple y",
                   "nipple z", "proj", "z_min", "lower/V", "gap", "newton", "time");
  for (std::size_t k = 0; k < rows.front().parameters.size(); ++k)
    s += fmt::format("{:>16} ", "");
  s += fmt::format("{:>9} {:>9} {:>9} {:>9} {:>9} {:>10} {:>9} {:>7} {:>7}\n", "[cm3]", "[mm]", "[mm]",
                   "[mm]", "[mm]", "", "[mm]", "", "[s]");
  for (const auto& r : rows)
  {
    for (const auto& [k, v] : r.parameters)
      s += fmt::format("{:>16} ", plain_text(v));
    if (!r.ok)
    {
      s += "rejected: " + r.error + "\n";
      continue;
    }
    s += fmt::format("{:>9.1f} {:>9.2f} {:>9.2f} {:>9.2f} {:>9.2f} {:>10.3f} {:>9.4f} {:>7d} {:>7.1f}\n",
                     1e6 * r.resected_volume, 1e3 * r.nipple[1], 1e3 * r.nipple[2], 1e3 * r.projection,
                     1e3 * r.z_min, r.lower_pole_share, 1e3 * r.max_gap, r.newton_iterations, r.seconds);
  }
  return s;
}
} // namespace breastsim
