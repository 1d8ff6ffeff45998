// SPDX-License-Identifier: LGPL-3.0-or-later
#include "http_reply.hpp"
#include "strict_json.hpp"
#include "errors.hpp"
#include <algorithm>
#include <fmt/format.h>
#include <memory>

namespace breastsim::app
{
namespace
{
constexpr int max_depth = 16;

/// Deepest nesting of [ and { outside strings (before parsing: a deeply
/// nested document is refused without recursing into it).
int nesting_depth(const std::string& text)
{
  int depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (char c : text)
  {
    if (in_string)
    {
      escaped = !escaped && c == '\\';
      if (c == '"' && !escaped)
        in_string = false;
      continue;
    }
    if (c == '"')
      in_string = true;
    else if (c == '[' || c == '{')
      deepest = std::max(deepest, ++depth);
    else if (c == ']' || c == '}')
      --depth;
  }
  return deepest;
}
} // namespace

void reply_bytes(httplib::Response& res, std::string body, const std::string& mime)
{
  if (body.empty())
    return res.set_content(body, mime);
  // A provider of known length is sent as it is; set_content would let
  // cpp-httplib brotli-compress text at quality 11 (about 1 s per MB here).
  auto bytes = std::make_shared<const std::string>(std::move(body));
  res.set_content_provider(bytes->size(), mime,
                           [bytes](size_t offset, size_t length, httplib::DataSink& sink) {
                             return sink.write(bytes->data() + offset,
                                               std::min(length, bytes->size() - offset));
                           });
}

bool has_body(const httplib::Response& res)
{
  return !res.body.empty() || res.content_length_ > 0;
}

void reply_json(httplib::Response& res, int status, const nlohmann::json& j)
{
  res.status = status;
  reply_bytes(res, j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& message)
{
  reply_json(res, status, {{"error", message}});
}

nlohmann::json parse_json_body(const httplib::Request& req)
{
  if (nesting_depth(req.body) > max_depth)
    throw InputError(fmt::format("the request body is nested deeper than {} levels", max_depth));
  try
  {
    return parse_json_strict(req.body);
  }
  catch (const DuplicateJsonKey& e)
  {
    throw InputError(fmt::format("the request body is ambiguous: {} (give each key once)", e.what()));
  }
  catch (const nlohmann::json::exception&)
  {
    throw InputError("the request body is not valid JSON");
  }
}

void with_json_body(const httplib::Request& req, httplib::Response& res,
                    const std::function<nlohmann::json(const nlohmann::json&)>& handle)
{
  const auto type = req.get_header_value("Content-Type");
  if (type.rfind("application/json", 0) != 0)
    return reply_error(res, 415, "send the request body as Content-Type: application/json");
  try
  {
    reply_json(res, 200, handle(parse_json_body(req)));
  }
  catch (const InputError& e)
  {
    reply_error(res, 400, e.what());
  }
}
} // namespace breastsim::app
