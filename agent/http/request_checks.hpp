// Checks of a request's head that need no route: whether its body is announced in a way the
// server accepts (Content-Length present, well formed, within the limit), and whether it
// carries the bearer key.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "agent/http/http_limits.hpp"

namespace a3::agent::http {

// For POST, PUT and PATCH: 411 without Content-Length (or with Transfer-Encoding: bodies must
// announce their length), 400 for a Content-Length that is not one decimal number (or several
// that differ), 413 above `max_body_bytes`. Other methods: 400 only for a malformed length.
std::optional<HttpRefusal> content_length_refusal(const httplib::Request& request, std::size_t max_body_bytes);

// True when `request_head` (a request's head exactly as received: GuardedServer::
// current_request_head(), not httplib's parsed headers, which are percent-decoded and cut at NUL)
// has exactly one Authorization header whose whole value, every byte, is "Bearer " + key
// (surrounding spaces and tabs aside, as HTTP allows). Compared in constant time for a given length.
bool bearer_key_matches(std::string_view request_head, const std::string& key);

// A client's header value as a refusal message shows it: at most `max_bytes`, control bytes as
// '?', "..." when cut.
std::string shown_header_value(const std::string& value, std::size_t max_bytes);

}  // namespace a3::agent::http
