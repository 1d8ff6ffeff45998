// SPDX-License-Identifier: LGPL-3.0-or-later
#include "serve_options.hpp"
#include "errors.hpp"
#include <fmt/format.h>

namespace breastsim::app
{
bool is_loopback(const std::string& host)
{
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

void check_serve_options(const ServeOptions& o)
{
  if (o.port < 0 || o.port > 65535)
    throw InputError(fmt::format("--port = {} is out of range: allowed [0, 65535] (0: any free port)",
                                 o.port));
  if (o.workers < 1 || o.workers > 16)
    throw InputError(fmt::format("--workers = {} is out of range: allowed [1, 16]", o.workers));
  if (o.max_body < 1024 || o.max_body > (64u << 20))
    throw InputError(fmt::format("--max-body = {} is out of range: allowed [1024, {}] bytes", o.max_body,
                                 64u << 20));
  if (o.max_upload < 1024 || o.max_upload > (1024u << 20))
    throw InputError(fmt::format("--max-upload = {} is out of range: allowed [1024, {}] bytes", o.max_upload,
                                 1024u << 20));
  if (o.host.empty())
    throw InputError("--host is empty: give an address, e.g. 127.0.0.1");
  if (!o.host_given && !is_loopback(o.host))
    throw InputError(fmt::format("--host {} must be given explicitly to listen beyond this machine",
                                 o.host));
  if (o.data.empty())
    throw InputError("--data is empty: give a folder name");
}
} // namespace breastsim::app
