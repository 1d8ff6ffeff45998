// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Requests whose headers are ambiguous or abusive are answered 400 before any
// routing (RFC 9112 section 3.2 and 6.3): more than one Host, an empty Host,
// no Host on HTTP/1.1, Content-Length given twice or with Transfer-Encoding,
// more than max_request_headers header lines.
#include <cstddef>
#include <httplib.h>
#include <optional>
#include <string>

namespace breastsim::app
{
inline constexpr std::size_t max_request_headers = 100;

/// Why the headers of `req` are refused (the 400 message), or nothing.
std::optional<std::string> malformed_headers(const httplib::Request& req);
} // namespace breastsim::app
