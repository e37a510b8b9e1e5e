// When and how long the LLM client waits before trying a chat-completions request again:
// which HTTP statuses and libcurl errors are worth a retry, the Retry-After header (seconds or
// an HTTP date), and the exponential backoff, capped.
#pragma once

#include <ctime>
#include <optional>
#include <string>

namespace a3::agent::llm {

// 429, 500, 502, 503, 504 (and 529, "overloaded", which some providers send) are retried;
// every other status is an answer.
bool is_retryable_http_status(int http_status);

// Network errors worth a retry: refused or failed connection, timeout, reset, a connection that
// died mid-answer, name resolution (CURLcode values; others, e.g. a malformed URL, are final).
bool is_retryable_curl_error(int curl_code);

// A Retry-After value: delay-seconds ("2", "1.5") or an HTTP date, relative to `now`.
// Nothing when absent or unreadable; never negative.
std::optional<double> parse_retry_after_s(const std::string& value, std::time_t now);

// Seconds to wait before retry number `retry_index` (0 = the first retry): initial * 2^index,
// or the server's Retry-After when it sent one, both capped at max_s.
double backoff_delay_s(int retry_index, double initial_s, double max_s, std::optional<double> retry_after_s);

}  // namespace a3::agent::llm
