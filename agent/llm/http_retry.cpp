// Retry policy of the LLM client.
#include "agent/llm/http_retry.hpp"

#include <curl/curl.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace a3::agent::llm {

bool is_retryable_http_status(int http_status) {
  switch (http_status) {
    case 429:
    case 500:
    case 502:
    case 503:
    case 504:
    case 529:
      return true;
    default:
      return false;
  }
}

bool is_retryable_curl_error(int curl_code) {
  switch (static_cast<CURLcode>(curl_code)) {
    case CURLE_COULDNT_RESOLVE_HOST:
    case CURLE_COULDNT_RESOLVE_PROXY:
    case CURLE_COULDNT_CONNECT:
    case CURLE_OPERATION_TIMEDOUT:
    case CURLE_SEND_ERROR:
    case CURLE_RECV_ERROR:
    case CURLE_GOT_NOTHING:
    case CURLE_PARTIAL_FILE:
    case CURLE_SSL_CONNECT_ERROR:
    case CURLE_HTTP2:
    case CURLE_HTTP2_STREAM:
      return true;
    default:
      return false;
  }
}

std::optional<double> parse_retry_after_s(const std::string& value, std::time_t now) {
  std::size_t begin = 0, end = value.size();
  while (begin < end && std::isspace(static_cast<unsigned char>(value[begin]))) ++begin;
  while (end > begin && std::isspace(static_cast<unsigned char>(value[end - 1]))) --end;
  const std::string text = value.substr(begin, end - begin);
  if (text.empty()) return std::nullopt;
  if (std::isdigit(static_cast<unsigned char>(text[0]))) {
    try {
      std::size_t used = 0;
      const double s = std::stod(text, &used);
      if (used == text.size() && std::isfinite(s)) return std::max(0.0, s);
    } catch (const std::exception&) {
    }
    return std::nullopt;
  }
  const std::time_t when = curl_getdate(text.c_str(), nullptr);
  if (when == -1) return std::nullopt;
  return std::max(0.0, std::difftime(when, now));
}

double backoff_delay_s(int retry_index, double initial_s, double max_s, std::optional<double> retry_after_s) {
  double delay_s = retry_after_s ? *retry_after_s : initial_s * std::ldexp(1.0, std::clamp(retry_index, 0, 60));
  return std::clamp(delay_s, 0.0, std::max(0.0, max_s));
}

}  // namespace a3::agent::llm
