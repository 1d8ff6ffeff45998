// SPDX-License-Identifier: LGPL-3.0-or-later
#pragma once
// Replies: bytes with their type; of the JSON API a document with a
// status, an error {"error": message} with its status, and the common
// handling of a POST body (must be application/json, nested at most 16
// levels, parsed; an InputError from the handler becomes 400 with the
// library's message).
#include <functional>
#include <httplib.h>
#include <nlohmann/json.hpp>
#include <string>

namespace breastsim::app
{
/// `body` as it is (uncompressed: on loopback sending is faster than
/// compressing), with its length.
void reply_bytes(httplib::Response& res, std::string body, const std::string& mime);
/// Whether a handler has given `res` a body.
bool has_body(const httplib::Response& res);
void reply_json(httplib::Response& res, int status, const nlohmann::json& j);
void reply_error(httplib::Response& res, int status, const std::string& message);
/// Parse the request body as JSON; InputError (the reason) if it is not.
nlohmann::json parse_json_body(const httplib::Request& req);
/// Run `handle` on the parsed body: 415 for another content type, 400 for
/// malformed JSON or an InputError, 200 with the returned document.
void with_json_body(const httplib::Request& req, httplib::Response& res,
                    const std::function<nlohmann::json(const nlohmann::json&)>& handle);
} // namespace breastsim::app
