// SPDX-License-Identifier: LGPL-3.0-or-later
#include "app_server.hpp"
#include "data_folder.hpp"
#include "errors.hpp"
#include "http_reply.hpp"
#include "job_api.hpp"
#include "plan_api.hpp"
#include "recording_api.hpp"
#include "report_api.hpp"
#include "request_headers.hpp"
#include "request_pool.hpp"
#include "scan_upload.hpp"
#include "static_files.hpp"
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <sstream>
#include <sys/socket.h>

namespace breastsim::app
{
namespace
{
/// cpp-httplib 0.11 listens with a backlog of 5 connections; a burst of
/// concurrent clients then sees resets. Linux lets listen() on a listening
/// socket raise the backlog.
class Server : public httplib::Server
{
public:
  void raise_backlog(int n) { ::listen(svr_sock_, n); }
};

/// Host header values a loopback server answers (the rest: DNS rebinding).
bool host_header_allowed(const std::string& host, int port)
{
  if (host.empty())
    return true; // HTTP/1.0 clients; browsers always send it
  const auto colon = host.rfind(':');
  const bool has_port = colon != std::string::npos && host.back() != ']';
  if (has_port && host.substr(colon + 1) != std::to_string(port))
    return false;
  const std::string name = has_port ? host.substr(0, colon) : host;
  return name == "127.0.0.1" || name == "localhost" || name == "[::1]";
}

/// A page's file with a validator (size and modification time): the
/// browser revalidates it on each load (304 while unchanged), which also
/// lets it keep the compiled code of three.js.
void reply_static(const httplib::Request& req, httplib::Response& res)
{
  const auto f = static_file(req.path);
  std::error_code ec;
  const auto size = std::filesystem::file_size(f->file, ec);
  const auto time = std::filesystem::last_write_time(f->file, ec);
  std::ifstream in(f->file, std::ios::binary);
  if (ec || !in)
    return reply_error(res, 404, "the page's file " + f->file.filename().string() + " is missing");
  const std::string etag = fmt::format("\"{:x}-{:x}\"", size, static_cast<std::uint64_t>(time.time_since_epoch().count()));
  res.headers.erase("Cache-Control");
  res.set_header("Cache-Control", "no-cache");
  res.set_header("ETag", etag);
  if (req.get_header_value("If-None-Match") == etag)
  {
    res.status = 304;
    return;
  }
  std::ostringstream s;
  s << in.rdbuf();
  reply_bytes(res, s.str(), f->mime);
}

void add_static_routes(httplib::Server& server)
{
  for (const auto& url : static_urls())
    server.Get(url, reply_static);
}

void add_plan_routes(httplib::Server& server)
{
  server.Get("/api/keys", [](const httplib::Request&, httplib::Response& res) {
    reply_json(res, 200, keys_document());
  });
  server.Post("/api/validate", [](const httplib::Request& req, httplib::Response& res) {
    with_json_body(req, res, validate_overrides);
  });
  server.Post("/api/incision/check", [](const httplib::Request& req, httplib::Response& res) {
    with_json_body(req, res, check_incision);
  });
  server.Post("/api/measurements/check", [](const httplib::Request& req, httplib::Response& res) {
    with_json_body(req, res, check_measurements);
  });
  server.Post("/api/recording/check", [](const httplib::Request& req, httplib::Response& res) {
    with_json_body(req, res, recording_check_answer);
  });
}

/// Before a POST body is read: every POST is JSON, but the scan upload's
/// bytes (application/octet-stream); neither is a type a cross-site form can
/// send without a preflight, which is never granted. Bodies above --max-body
/// (--max-upload for the scan upload) get 413, a body of unstated length 411.
bool refuse_body(const httplib::Request& req, httplib::Response& res, const ServeOptions& o)
{
  if (req.method != "POST")
    return false;
  const bool upload = req.path == "/api/scans";
  if (!upload && req.get_header_value("Content-Type").rfind("application/json", 0) != 0)
    reply_error(res, 415, "send the request body as Content-Type: application/json");
  else if (!req.has_header("Content-Length") && req.has_header("Transfer-Encoding"))
    reply_error(res, 411, "send the request body with its Content-Length");
  else if (req.get_header_value<std::uint64_t>("Content-Length") > (upload ? o.max_upload : o.max_body))
    reply_error(res, 413, upload ? fmt::format("the scan file is too large: at most {} bytes (--max-upload)", o.max_upload)
                                 : std::string("the request body is too large"));
  else
    return false;
  res.set_header("Connection", "close"); // the body is not read
  return true;
}

/// Limits, headers and the handlers of errors and exceptions.
void configure(httplib::Server& server, const ServeOptions& o, const int& port)
{
  const int threads = o.http_threads;
  server.new_task_queue = [threads] { return new RequestPool(threads, 256); };
  server.set_payload_max_length(std::max(o.max_body, o.max_upload)); // the rest: refuse_body below
  server.set_read_timeout(5, 0);
  server.set_write_timeout(5, 0);
  server.set_tcp_nodelay(true); // a reply's headers and body leave at once (no 40 ms delayed ACK)
  server.set_keep_alive_max_count(20);
  server.set_keep_alive_timeout(2);
  server.set_default_headers({{"X-Content-Type-Options", "nosniff"},
                              {"X-Frame-Options", "DENY"},
                              {"Cache-Control", "no-store"}});
  const bool loopback = !o.host_given || is_loopback(o.host);
  server.set_pre_routing_handler([loopback, &port, o](const httplib::Request& req, httplib::Response& res) {
    if (auto why = malformed_headers(req))
    {
      reply_error(res, 400, *why);
      res.set_header("Connection", "close");
      return httplib::Server::HandlerResponse::Handled;
    }
    if (loopback && !host_header_allowed(req.get_header_value("Host"), port))
    {
      reply_error(res, 403, "this server answers only requests addressed to 127.0.0.1 or localhost");
      return httplib::Server::HandlerResponse::Handled;
    }
    return refuse_body(req, res, o) ? httplib::Server::HandlerResponse::Handled
                                    : httplib::Server::HandlerResponse::Unhandled;
  });
  server.set_error_handler(httplib::Server::HandlerWithResponse(
      [](const httplib::Request&, httplib::Response& res) {
    if (!has_body(res))
      reply_error(res, res.status, res.status == 413 ? "the request body is too large"
                                   : res.status == 404 ? "not found"
                                                       : "request refused (HTTP " + std::to_string(res.status) + ")");
    return httplib::Server::HandlerResponse::Handled;
  }));
  server.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
    try
    {
      std::rethrow_exception(ep);
    }
    catch (const InputError& e)
    {
      reply_error(res, 400, e.what());
    }
    catch (const std::exception& e)
    {
      reply_error(res, 500, std::string("internal error: ") + e.what());
    }
    catch (...)
    {
      reply_error(res, 500, "internal error");
    }
  });
}
} // namespace

int serve(const ServeOptions& o)
{
  check_serve_options(o);
  const auto data = claim_data_folder(o.data);
  JobStore store(data);
  Server server;
  int port = o.port;
  configure(server, o, port);
  const bool bound = o.port == 0 ? (port = server.bind_to_any_port(o.host)) > 0
                                 : server.bind_to_port(o.host, o.port);
  if (!bound)
    throw InputError(fmt::format("--host {} --port {}: cannot listen there (in use, or not an address "
                                 "of this machine)", o.host, o.port));
  server.raise_backlog(512);
  JobQueue queue(store, o.program, o.workers, o.max_queued);
  add_static_routes(server);
  add_plan_routes(server);
  add_job_routes(server, store, queue);
  add_report_routes(server, store);
  add_scan_routes(server, store, queue, data);
  const std::string shown = o.host.find(':') != std::string::npos ? "[" + o.host + "]" : o.host;
  std::cout << fmt::format("breastsim serve: listening on http://{}:{}/ (data {}, {} worker{})", shown,
                           port, data.string(), o.workers, o.workers == 1 ? "" : "s")
            << std::endl;
  server.listen_after_bind();
  return 0;
}
} // namespace breastsim::app
