// The body of a POST to `a3rig serve-model`, by its Content-Type: JSON is what it takes
// ("application/json", with parameters such as "; charset=utf-8", or "+json" types; a missing
// Content-Type or text/plain is taken when the body parses as JSON). Form bodies
// (application/x-www-form-urlencoded, multipart/*) are refused with 415 before the body is read;
// any other body that is not JSON gets 415 (a JSON type whose body does not parse: 400).
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

#include "agent/model_server/openai_error.hpp"

namespace a3::agent::model_server {

// "application/json" from "Application/JSON; charset=utf-8"; "" when none.
std::string media_type(const std::string& content_type);
// The 415 for a media type whose body is never JSON (forms), else nothing.
std::optional<ApiError> form_body_error(const std::string& media);
// Parses `body` into `out`; the 400 / 415 when it is not JSON.
std::optional<ApiError> parse_json_body(const std::string& body, const std::string& media, nlohmann::json& out);

}  // namespace a3::agent::model_server
