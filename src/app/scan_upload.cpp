// SPDX-License-Identifier: LGPL-3.0-or-later
#include "scan_upload.hpp"
#include "errors.hpp"
#include "http_reply.hpp"
#include "job_id.hpp"
#include "scan_checks.hpp"
#include "scan_readers.hpp"
#include <charconv>
#include <fmt/format.h>
#include <fstream>
#include <set>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
std::string one_of(const std::multimap<std::string, std::string>& params, const std::string& name,
                   const std::set<std::string>& allowed, const std::string& fallback)
{
  if (params.count(name) > 1)
    throw InputError(fmt::format("field '{}' is given {} times: give it once", name, params.count(name)));
  const auto it = params.find(name);
  const std::string v = it == params.end() ? fallback : it->second;
  if (!allowed.count(v))
  {
    std::string names;
    for (const auto& a : allowed)
      names += (names.empty() ? "" : ", ") + a;
    throw InputError(fmt::format("{} = '{}': allowed {}", name, v.substr(0, 40), names));
  }
  return v;
}

double mesh_size_of(const std::multimap<std::string, std::string>& params)
{
  const auto it = params.find("mesh_size");
  if (it == params.end())
    return 0;
  const std::string& text = it->second;
  double v = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || !(v == 0 || (v >= 0.001 && v <= 0.02)))
    throw InputError(fmt::format("mesh_size = {} is out of range: allowed 0 (by the breast's volume) or "
                                 "[0.001, 0.02] m", text.substr(0, 40)));
  return v;
}

void reply_scan_job(const httplib::Request& req, httplib::Response& res, JobStore& store, JobQueue& queue,
                    const fs::path& uploads)
{
  if (req.get_header_value("Content-Type").rfind("application/octet-stream", 0) != 0)
    return reply_error(res, 415, "send the scan file's bytes as Content-Type: application/octet-stream");
  const ScanUpload u = checked_scan_upload(req.params);
  const fs::path file = uploads / (new_job_id() + "." + u.format);
  {
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    f.write(req.body.data(), static_cast<std::streamsize>(req.body.size()));
  }
  try
  {
    check_uploaded_scan(file, u);
  }
  catch (...)
  {
    fs::remove(file);
    throw;
  }
  const std::string name = "scan." + u.format;
  const auto r = store.create({{"kind", "scan"}, {"overrides", nlohmann::json::object()},
                               {"scan", {{"file", name}, {"format", u.format}, {"units", u.units},
                                         {"posture", u.posture}, {"mesh_size", u.mesh_size}, {"use", u.use},
                                         {"bytes", req.body.size()}}}});
  fs::rename(file, store.folder(r.id) / name);
  if (!submit_or_fail(store, queue, r.id))
    return reply_error(res, 429, "the job queue is full: try again when a job has finished");
  reply_json(res, 202, {{"id", r.id}});
}
} // namespace

ScanUpload checked_scan_upload(const std::multimap<std::string, std::string>& params)
{
  for (const auto& [k, _] : params)
    if (k != "format" && k != "units" && k != "posture" && k != "mesh_size" && k != "use")
      throw InputError(fmt::format("field '{}' is not allowed in a scan upload (allowed: format, mesh_size, "
                                   "posture, units, use)", k.substr(0, 40)));
  ScanUpload u;
  u.format = one_of(params, "format", {"stl", "ply", "obj"}, "");
  if (params.count("units") != 1)
    throw InputError("units: the unit of the scan's coordinates must be stated: mm or m");
  u.units = params.find("units")->second;
  scan::parse_units(u.units, "units");
  u.posture = one_of(params, "posture", {"standing", "supine", "all_fours"}, "standing");
  u.mesh_size = mesh_size_of(params);
  u.use = one_of(params, "use", {"model", "consultation"}, "model");
  if (u.use == "consultation" && u.posture != "standing")
    throw InputError("posture = " + u.posture + ": a consultation's scan is taken standing");
  return u;
}

void check_uploaded_scan(const fs::path& file, const ScanUpload& u)
{
  try
  {
    scan::check_scan(scan::read_scan(file, scan::parse_units(u.units, "units")), scan::ScanLimits{});
  }
  catch (const InputError& e)
  {
    std::string m = e.what();
    for (const std::string& name : {file.string(), file.filename().string()})
      for (auto p = m.find(name); p != std::string::npos; p = m.find(name))
        m.replace(p, name.size(), "the uploaded scan");
    throw InputError(m);
  }
}

void add_scan_routes(httplib::Server& server, JobStore& store, JobQueue& queue, const fs::path& data)
{
  const fs::path uploads = data / "uploads";
  fs::remove_all(uploads); // files of a server stopped while checking them
  fs::create_directories(uploads);
  server.Post("/api/scans", [&store, &queue, uploads](const httplib::Request& req, httplib::Response& res) {
    reply_scan_job(req, res, store, queue, uploads);
  });
}
} // namespace breastsim::app
