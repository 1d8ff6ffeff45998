// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// The options of `breastsim serve` (the planning app's HTTP server), checked
// once at the edge with messages naming the option, the value and the range.
#include <cstddef>
#include <filesystem>
#include <string>

namespace breastsim::app
{
struct ServeOptions
{
  std::string host = "127.0.0.1";   ///< address to listen on (loopback unless given)
  bool host_given = false;          ///< --host given explicitly
  int port = 8080;                  ///< 0: any free port (printed at start)
  std::string data = "results/serve"; ///< folder of the job records and results
  int workers = 1;                  ///< solver processes running at the same time
  std::size_t max_body = 1 << 20;   ///< largest request body [bytes]
  std::size_t max_upload = 64u << 20; ///< largest scan upload (POST /api/scans) [bytes]
  std::size_t max_queued = 64;      ///< jobs waiting at most; more are refused (429)
  int http_threads = 64;            ///< threads answering requests (a slow client holds one)
  std::string program;              ///< this program (/proc/self/exe), run for each job
};

/// Range checks of every option; throws InputError naming the option.
void check_serve_options(const ServeOptions& o);
/// True for 127.0.0.0/8, ::1 and localhost.
bool is_loopback(const std::string& host);
} // namespace breastsim::app
