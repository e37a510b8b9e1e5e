// Range checks of HttpLimits (see http_limits.hpp).
#include "agent/http/http_limits.hpp"

#include <cstdio>
#include <stdexcept>

namespace a3::agent::http {
namespace {

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", s);
  return text;
}

}  // namespace

void check_http_limits(const HttpLimits& limits) {
  if (limits.max_connections < 1) {
    throw std::invalid_argument("--max-connections " + std::to_string(limits.max_connections) + ": must be >= 1");
  }
  if (!(limits.header_timeout_s > 0.0 && limits.header_timeout_s <= 3600.0)) {
    throw std::invalid_argument("--header-timeout " + seconds_text(limits.header_timeout_s) + ": must be in (0, 3600] s");
  }
  if (!(limits.body_timeout_s > 0.0 && limits.body_timeout_s <= 3600.0)) {
    throw std::invalid_argument("--body-timeout " + seconds_text(limits.body_timeout_s) + ": must be in (0, 3600] s");
  }
  if (!(limits.write_timeout_s > 0.0 && limits.write_timeout_s <= 3600.0)) {
    throw std::invalid_argument("write timeout " + seconds_text(limits.write_timeout_s) + ": must be in (0, 3600] s");
  }
}

}  // namespace a3::agent::http
