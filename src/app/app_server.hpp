// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// `breastsim serve`: the planning app's HTTP server (cpp-httplib). One page
// and a JSON API over the library: the case schema and checks answered at
// once (plan_api), long work as jobs (job_queue, job_api). Listens on
// loopback unless --host is given; refuses requests whose Host header names
// another machine (DNS rebinding) when on loopback; no CORS headers; request
// bodies above max_body get 413; every handler's exception becomes a JSON
// error, never the end of the server.
#include "serve_options.hpp"

namespace breastsim::app
{
/// Claim the data folder, start the workers, listen until SIGINT/SIGTERM.
/// Prints "listening on http://HOST:PORT/" once bound. Returns 0, or throws
/// InputError (bad options, data folder refused, port taken).
int serve(const ServeOptions& o);
} // namespace breastsim::app
