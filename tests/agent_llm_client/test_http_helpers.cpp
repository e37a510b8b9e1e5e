// The client's pieces on their own: Retry-After, backoff, retryable statuses, response reading,
// usage sums, redaction.
#include <gtest/gtest.h>

#include <curl/curl.h>

#include "agent/llm/http_chat_completion.hpp"
#include "agent/llm/http_retry.hpp"
#include "agent/llm/llm_client.hpp"

namespace {

using namespace a3::agent::llm;
using nlohmann::json;

TEST(RetryAfter, SecondsAndHttpDates) {
  const std::time_t now = curl_getdate("Wed, 21 Oct 2015 07:28:00 GMT", nullptr);
  ASSERT_NE(now, -1);
  EXPECT_EQ(parse_retry_after_s("2", now), 2.0);
  EXPECT_EQ(parse_retry_after_s(" 1.5 ", now), 1.5);
  EXPECT_EQ(parse_retry_after_s("Wed, 21 Oct 2015 07:28:07 GMT", now), 7.0);
  EXPECT_EQ(parse_retry_after_s("Wed, 21 Oct 2015 07:27:00 GMT", now), 0.0);  // in the past
  EXPECT_FALSE(parse_retry_after_s("", now).has_value());
  EXPECT_FALSE(parse_retry_after_s("soon", now).has_value());
  EXPECT_FALSE(parse_retry_after_s("2s", now).has_value());
}

TEST(Backoff, DoublesFromTheInitialDelayUpToTheCapAndRetryAfterOverrides) {
  EXPECT_EQ(backoff_delay_s(0, 1.0, 30.0, std::nullopt), 1.0);
  EXPECT_EQ(backoff_delay_s(3, 1.0, 30.0, std::nullopt), 8.0);
  EXPECT_EQ(backoff_delay_s(10, 1.0, 30.0, std::nullopt), 30.0);
  EXPECT_EQ(backoff_delay_s(0, 1.0, 30.0, 4.0), 4.0);
  EXPECT_EQ(backoff_delay_s(0, 1.0, 30.0, 120.0), 30.0);
}

TEST(RetryPolicy, WhichStatusesAndErrorsAreRetried) {
  for (int s : {429, 500, 502, 503, 504}) EXPECT_TRUE(is_retryable_http_status(s)) << s;
  for (int s : {200, 400, 401, 403, 404, 408, 413, 422, 501}) EXPECT_FALSE(is_retryable_http_status(s)) << s;
  EXPECT_TRUE(is_retryable_curl_error(CURLE_COULDNT_CONNECT));
  EXPECT_TRUE(is_retryable_curl_error(CURLE_OPERATION_TIMEDOUT));
  EXPECT_TRUE(is_retryable_curl_error(CURLE_RECV_ERROR));
  EXPECT_FALSE(is_retryable_curl_error(CURLE_URL_MALFORMAT));
  EXPECT_FALSE(is_retryable_curl_error(CURLE_WRITE_ERROR));
}

TEST(ChatResponse, UsageWithoutTotalIsSummedAndCostIsOptional) {
  ChatResponse r;
  std::string error;
  const std::string body =
      R"({"choices":[{"message":{"content":"hi"},"finish_reason":"length"}],"usage":{"prompt_tokens":3,"completion_tokens":4}})";
  ASSERT_TRUE(parse_chat_response(body, "u", r, error)) << error;
  EXPECT_EQ(r.content, "hi");
  EXPECT_EQ(r.finish_reason, "length");
  EXPECT_EQ(r.usage.total_tokens, 7);
  EXPECT_FALSE(r.usage.cost_usd.has_value());
}

// Fuzz finding (llm_reply): a count of 7.8e99 was cast to int64 (undefined behaviour).
TEST(ChatResponse, AbsurdTokenCountsCountAsZero) {
  ChatResponse r;
  std::string error;
  const std::string body =
      R"({"choices":[{"message":{"content":"hi"}}],"usage":{"prompt_tokens":7.8e99,)"
      R"("completion_tokens":-5,"total_tokens":18446744073709551615}})";
  ASSERT_TRUE(parse_chat_response(body, "u", r, error)) << error;
  EXPECT_EQ(r.usage.prompt_tokens, 0);
  EXPECT_EQ(r.usage.completion_tokens, 0);
  EXPECT_EQ(r.usage.total_tokens, 0);
}

TEST(ChatResponse, WrongShapesAreNamed) {
  ChatResponse r;
  std::string error;
  EXPECT_FALSE(parse_chat_response("[1,2]", "u", r, error));
  EXPECT_NE(error.find("not a JSON object"), std::string::npos);
  EXPECT_FALSE(parse_chat_response(R"({"choices":[{"text":"old completions API"}]})", "u", r, error));
  EXPECT_NE(error.find("no choices[0].message"), std::string::npos);
  EXPECT_FALSE(parse_chat_response(R"({"choices":[{"message":{"content":42}}]})", "u", r, error));
  EXPECT_NE(error.find("no choices[0].message.content"), std::string::npos);
  EXPECT_FALSE(parse_chat_response("", "u", r, error));
  EXPECT_NE(error.find("body starts: (empty)"), std::string::npos) << error;
}

TEST(BodyExcerpt, OneLineAndCut) {
  EXPECT_EQ(body_excerpt("a\nb\tc\x01", 100), "a\\nb\\tc\\x01");
  EXPECT_EQ(body_excerpt(std::string(10, 'x'), 4), "xxxx…");
}

TEST(LlmUsage, SumsTokensCostAndNestedFields) {
  LlmUsage a;
  a.prompt_tokens = 10;
  a.completion_tokens = 5;
  a.total_tokens = 15;
  a.cost_usd = 0.01;
  a.raw = {{"prompt_tokens", 10}, {"completion_tokens", 5}, {"total_tokens", 15}, {"cost", 0.01},
           {"is_byok", false}, {"completion_tokens_details", {{"reasoning_tokens", 2}}}};
  LlmUsage b;
  b.prompt_tokens = 1;
  b.completion_tokens = 2;
  b.total_tokens = 3;
  b.raw = {{"prompt_tokens", 1}, {"completion_tokens", 2}, {"total_tokens", 3},
           {"completion_tokens_details", {{"reasoning_tokens", 1}, {"image_tokens", 0}}}};
  a += b;
  EXPECT_EQ(a.prompt_tokens, 11);
  EXPECT_EQ(a.completion_tokens, 7);
  EXPECT_EQ(a.total_tokens, 18);
  EXPECT_DOUBLE_EQ(*a.cost_usd, 0.01);
  const json j = a.to_json();
  EXPECT_EQ(j["total_tokens"], 18);
  EXPECT_EQ(j["is_byok"], false);
  EXPECT_EQ(j["completion_tokens_details"]["reasoning_tokens"], 3);
  EXPECT_EQ(j["completion_tokens_details"]["image_tokens"], 0);
  EXPECT_DOUBLE_EQ(j["cost"].get<double>(), 0.01);

  LlmUsage empty;
  EXPECT_EQ(empty.to_json(), json({{"prompt_tokens", 0}, {"completion_tokens", 0}, {"total_tokens", 0}}));
}

TEST(Redact, EveryOccurrence) {
  EXPECT_EQ(redact("k=SECRET and SECRET again", "SECRET"), "k=[redacted] and [redacted] again");
  EXPECT_EQ(redact("nothing here", ""), "nothing here");
  EXPECT_EQ(redact("aaaa", "aa"), "[redacted][redacted]");
}

}  // namespace
