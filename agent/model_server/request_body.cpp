// Checking a POST body's media type and parsing it as JSON.
#include "agent/model_server/request_body.hpp"

#include <algorithm>
#include <cctype>

#include "common/json_text.hpp"

namespace a3::agent::model_server {
namespace {

bool is_json_type(const std::string& media) {
  const std::string suffix = "+json";
  return media == "application/json" ||
         (media.size() > suffix.size() && media.compare(media.size() - suffix.size(), suffix.size(), suffix) == 0);
}

ApiError unsupported(const std::string& media, const std::string& why) {
  return {415, "the request body must be application/json (got Content-Type: " + media + why + ")", std::nullopt,
          "unsupported_media_type"};
}

}  // namespace

std::string media_type(const std::string& content_type) {
  std::string media = content_type.substr(0, content_type.find(';'));
  const auto not_space = [](unsigned char c) { return !std::isspace(c); };
  media.erase(media.begin(), std::find_if(media.begin(), media.end(), not_space));
  media.erase(std::find_if(media.rbegin(), media.rend(), not_space).base(), media.end());
  std::transform(media.begin(), media.end(), media.begin(), [](unsigned char c) { return std::tolower(c); });
  return media;
}

std::optional<ApiError> form_body_error(const std::string& media) {
  if (media == "application/x-www-form-urlencoded" || media.rfind("multipart/", 0) == 0) {
    return unsupported(media, ", a form");
  }
  return std::nullopt;
}

std::optional<ApiError> parse_json_body(const std::string& body, const std::string& media, nlohmann::json& out) {
  std::string problem;
  if (auto parsed = common::try_parse_json_text(body, &problem)) {
    out = std::move(*parsed);
    return std::nullopt;
  }
  if (media.empty() || is_json_type(media)) {
    return ApiError{400, "the request body is not JSON (" + problem +
                             "); send a JSON object with Content-Type: application/json",
                    std::nullopt, "invalid_json"};
  }
  return unsupported(media, ", and the body is not JSON");
}

}  // namespace a3::agent::model_server
