// SPDX-License-Identifier: LGPL-3.0-or-later
#include "job_api.hpp"
#include "errors.hpp"
#include "http_reply.hpp"
#include "job_evaluations.hpp"
#include "job_request.hpp"
#include "result_archive.hpp"
#include "scan_job.hpp"
#include <fstream>
#include <sstream>

namespace breastsim::app
{
namespace fs = std::filesystem;
namespace
{
std::string mime_of(const fs::path& p)
{
  const auto ext = p.extension().string();
  if (ext == ".json")
    return "application/json";
  if (ext == ".html")
    return "text/html; charset=utf-8";
  if (ext == ".png")
    return "image/png";
  if (ext == ".csv")
    return "text/csv; charset=utf-8";
  return "text/plain; charset=utf-8";
}

/// The file `name` of job `id` if its record lists it and it lies inside
/// the job's folder; empty otherwise.
fs::path job_file(const JobStore& store, const std::string& id, const std::string& name)
{
  const auto r = store.get(id);
  if (!r)
    return {};
  const auto it = r->files.find(name);
  if (it == r->files.end())
    return {};
  const fs::path folder = fs::weakly_canonical(store.folder(id));
  const fs::path file = fs::weakly_canonical(folder / it->second);
  const auto rel = file.lexically_relative(folder);
  if (rel.empty() || *rel.begin() == ".." || !fs::is_regular_file(file))
    return {};
  return file;
}

/// A scanned breast's surgery names a finished scan job of this server,
/// whose neutral case exists (the request's id only: no path).
void check_scan_of(const nlohmann::json& request, const JobStore& store)
{
  if (!request.contains("scan"))
    return;
  const std::string id = request["scan"];
  const auto scan = store.get(id);
  if (!scan || scan->kind != "scan" || scan->state != JobState::done ||
      !fs::is_regular_file(store.folder(id) / scan_neutral_case))
    throw InputError("scan = \"" + id + "\": not a finished scan job of this server (upload the scan and wait "
                     "until its job is done)");
}

void post_job(const httplib::Request& req, httplib::Response& res, JobStore& store, JobQueue& queue)
{
  std::string id;
  with_json_body(req, res, [&](const nlohmann::json& body) {
    const auto request = checked_job_request(body);
    check_scan_of(request, store);
    const auto r = store.create(request);
    id = r.id;
    if (!submit_or_fail(store, queue, r.id))
      id.clear();
    return nlohmann::json{{"id", r.id}};
  });
  if (res.status == 200 && id.empty())
    reply_error(res, 429, "the job queue is full: try again when a job has finished");
  else if (res.status == 200)
    res.status = 202;
}
} // namespace

nlohmann::json public_record(const JobRecord& r)
{
  auto j = to_json(r);
  j.erase("file_paths");
  return j;
}

void add_job_routes(httplib::Server& server, JobStore& store, JobQueue& queue)
{
  server.Post("/api/jobs", [&](const httplib::Request& req, httplib::Response& res) {
    post_job(req, res, store, queue);
  });
  server.Get("/api/jobs", [&](const httplib::Request&, httplib::Response& res) {
    nlohmann::json jobs = nlohmann::json::array();
    for (const auto& r : store.list())
      jobs.push_back(public_record(r));
    reply_json(res, 200, {{"jobs", jobs}});
  });
  // A calibration's record carries its evaluations (those after `since`).
  server.Get(R"(/api/jobs/([0-9a-f]{16}))", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto r = store.get(id);
    if (!r)
      return reply_error(res, 404, "no such job");
    auto j = public_record(*r);
    if (r->kind == "calibrate")
    {
      long since = 0;
      try
      {
        since = parse_since(req.has_param("since") ? req.get_param_value("since") : "");
      }
      catch (const InputError& e)
      {
        return reply_error(res, 400, e.what());
      }
      j["evaluations"] = read_evaluations(store.folder(id), since);
    }
    reply_json(res, 200, j);
  });
  server.Post(R"(/api/jobs/([0-9a-f]{16})/cancel)", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    if (!store.get(id))
      return reply_error(res, 404, "no such job");
    if (!queue.cancel(id))
      return reply_error(res, 409, "the job has already finished");
    reply_json(res, 200, {{"ok", true}, {"id", id}});
  });
  server.Get(R"(/api/jobs/([0-9a-f]{16})/result\.tar)", [&](const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto r = store.get(id);
    if (!r || r->state != JobState::done)
      return reply_error(res, 404, "no finished job with this id");
    reply_bytes(res, result_archive(store.folder(id) / "result", "breastsim-" + id, 512u << 20),
                "application/x-tar");
    res.set_header("Content-Disposition", "attachment; filename=\"breastsim-" + id + ".tar\"");
  });
  server.Get(R"(/api/jobs/([0-9a-f]{16})/files/([A-Za-z0-9_.=\-]{1,160}))",
             [&](const httplib::Request& req, httplib::Response& res) {
               const fs::path file = job_file(store, req.matches[1], req.matches[2]);
               if (file.empty())
                 return reply_error(res, 404, "no such file of this job");
               std::ifstream f(file, std::ios::binary);
               std::ostringstream s;
               s << f.rdbuf();
               reply_bytes(res, s.str(), mime_of(file));
             });
}
} // namespace breastsim::app
