// Content-Length admission and the bearer-key check (see request_checks.hpp).
#include "agent/http/request_checks.hpp"

#include <httplib.h>
#include <openssl/crypto.h>

namespace a3::agent::http {
namespace {

bool carries_body(const std::string& method) { return method == "POST" || method == "PUT" || method == "PATCH"; }

// The value as a byte count, or nullopt when it is not 1 to 19 decimal digits.
std::optional<std::size_t> parse_length(const std::string& value) {
  if (value.empty() || value.size() > 19) return std::nullopt;
  std::size_t n = 0;
  for (const char c : value) {
    if (c < '0' || c > '9') return std::nullopt;
    n = n * 10 + static_cast<std::size_t>(c - '0');
  }
  return n;
}

// Printable for a message: at most 40 bytes, control bytes as '?'.
std::string shown(const std::string& value) {
  std::string out = value.substr(0, 40);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return out + (value.size() > 40 ? "..." : "");
}

}  // namespace

std::optional<HttpRefusal> content_length_refusal(const httplib::Request& request, std::size_t max_body_bytes) {
  const bool body_expected = carries_body(request.method);
  if (body_expected && request.has_header("Transfer-Encoding")) {
    return HttpRefusal{411, "Content-Length required: send the body with a Content-Length header (Transfer-Encoding '" +
                                shown(request.get_header_value("Transfer-Encoding")) + "' is not accepted)"};
  }
  const auto [first, last] = request.headers.equal_range("Content-Length");
  if (first == last) {
    if (!body_expected) return std::nullopt;
    return HttpRefusal{411, "Content-Length required: " + request.method + " " + request.path +
                                " must send its body with a Content-Length header"};
  }
  std::optional<std::size_t> length;
  for (auto it = first; it != last; ++it) {
    const auto n = parse_length(it->second);
    if (!n) return HttpRefusal{400, "malformed Content-Length '" + shown(it->second) + "': must be a decimal byte count"};
    if (length && *length != *n) return HttpRefusal{400, "malformed Content-Length: several headers that differ"};
    length = n;
  }
  if (*length > max_body_bytes) {
    return HttpRefusal{413, "request body larger than " + std::to_string(max_body_bytes) + " bytes (Content-Length " +
                                std::to_string(*length) + ")"};
  }
  return std::nullopt;
}

bool bearer_key_matches(const httplib::Request& request, const std::string& key) {
  // The multimap's value, not get_header_value(), whose C string would end at a NUL byte.
  if (request.headers.count("Authorization") != 1) return false;
  const std::string& value = request.headers.find("Authorization")->second;
  const std::string expected = "Bearer " + key;
  if (value.size() != expected.size()) return false;
  return CRYPTO_memcmp(value.data(), expected.data(), expected.size()) == 0;
}

}  // namespace a3::agent::http
