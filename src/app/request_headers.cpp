// SPDX-License-Identifier: LGPL-3.0-or-later
#include "request_headers.hpp"
#include <fmt/format.h>

namespace breastsim::app
{
std::optional<std::string> malformed_headers(const httplib::Request& req)
{
  if (req.headers.size() > max_request_headers)
    return fmt::format("the request has {} header lines: at most {} are accepted", req.headers.size(),
                       max_request_headers);
  const std::size_t hosts = req.get_header_value_count("Host");
  if (hosts > 1)
    return fmt::format("the request has {} Host headers: send exactly one", hosts);
  if (hosts == 1 && req.get_header_value("Host").empty())
    return std::string("the request's Host header is empty");
  if (hosts == 0 && req.version != "HTTP/1.0")
    return std::string("the request has no Host header (required by HTTP/1.1)");
  if (req.get_header_value_count("Content-Length") > 1)
    return std::string("the request has more than one Content-Length header");
  if (req.has_header("Content-Length") && req.has_header("Transfer-Encoding"))
    return std::string("the request has both Content-Length and Transfer-Encoding");
  return std::nullopt;
}
} // namespace breastsim::app
