// Content-Length admission and the bearer-key check (see request_checks.hpp).
#include "agent/http/request_checks.hpp"

#include <httplib.h>
#include <openssl/crypto.h>

#include <cctype>
#include <vector>

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

bool is_space_or_tab(char c) { return c == ' ' || c == '\t'; }

bool equals_ignoring_case(std::string_view a, std::string_view lower) {
  if (a.size() != lower.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != lower[i]) return false;
  }
  return true;
}

// The values of the header `lower_name` in a raw head, surrounding spaces and tabs removed.
std::vector<std::string_view> header_values(std::string_view head, std::string_view lower_name) {
  std::vector<std::string_view> values;
  std::size_t line_start = head.find('\n');  // after the request line
  while (line_start != std::string_view::npos && line_start + 1 < head.size()) {
    const std::size_t begin = line_start + 1;
    std::size_t end = head.find('\n', begin);
    std::string_view line = head.substr(begin, end == std::string_view::npos ? std::string_view::npos : end - begin);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) break;  // the blank line ending the head
    const std::size_t colon = line.find(':');
    if (colon != std::string_view::npos && equals_ignoring_case(line.substr(0, colon), lower_name)) {
      std::string_view value = line.substr(colon + 1);
      while (!value.empty() && is_space_or_tab(value.front())) value.remove_prefix(1);
      while (!value.empty() && is_space_or_tab(value.back())) value.remove_suffix(1);
      values.push_back(value);
    }
    line_start = end;
  }
  return values;
}

}  // namespace

std::optional<HttpRefusal> content_length_refusal(const httplib::Request& request, std::size_t max_body_bytes) {
  const bool body_expected = carries_body(request.method);
  if (body_expected && request.has_header("Transfer-Encoding")) {
    return HttpRefusal{411, "Content-Length required: send the body with a Content-Length header (Transfer-Encoding '" +
                                shown_header_value(request.get_header_value("Transfer-Encoding"), 40) + "' is not accepted)"};
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
    if (!n) return HttpRefusal{400, "malformed Content-Length '" + shown_header_value(it->second, 40) + "': must be a decimal byte count"};
    if (length && *length != *n) return HttpRefusal{400, "malformed Content-Length: several headers that differ"};
    length = n;
  }
  if (*length > max_body_bytes) {
    return HttpRefusal{413, "request body larger than " + std::to_string(max_body_bytes) + " bytes (Content-Length " +
                                std::to_string(*length) + ")"};
  }
  return std::nullopt;
}

std::string shown_header_value(const std::string& value, std::size_t max_bytes) {
  std::string out = value.substr(0, max_bytes);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return out + (value.size() > max_bytes ? "..." : "");
}

bool bearer_key_matches(std::string_view request_head, const std::string& key) {
  std::vector<std::string_view> values = header_values(request_head, "authorization");
  if (values.size() != 1) return false;
  const std::string expected = "Bearer " + key;
  if (values.front().size() != expected.size()) return false;
  return CRYPTO_memcmp(values.front().data(), expected.data(), expected.size()) == 0;
}

}  // namespace a3::agent::http
