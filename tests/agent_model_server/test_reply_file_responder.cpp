// The reply-file responder: replies in turn, from files and texts, usage from characters, and
// clear errors for files it cannot use.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_file_responder.hpp"

namespace {

namespace ms = a3::agent::model_server;
using nlohmann::json;

const json kRequest = {{"model", "m"}, {"messages", {{{"role", "user"}, {"content", "0123456789"}}}}};

std::filesystem::path temp_file(const std::string& name, const std::string& content) {
  const auto path = std::filesystem::temp_directory_path() / ("a3_reply_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

TEST(ReplyFileResponder, CyclesRepliesFromFilesThenTexts) {
  const auto a = temp_file("a.json", "{\"intent\":\"a\"}\n");
  ms::ReplyFileResponderOptions o;
  o.files = {a.string()};
  o.texts = {"second"};
  auto r = ms::make_reply_file_responder(o);
  EXPECT_EQ(r->name(), "reply-file");
  EXPECT_EQ(r->respond(kRequest).content, "{\"intent\":\"a\"}\n");
  EXPECT_EQ(r->respond(kRequest).content, "second");
  EXPECT_EQ(r->respond(kRequest).content, "{\"intent\":\"a\"}\n");
  std::filesystem::remove(a);
}

TEST(ReplyFileResponder, UsageIsFourCharactersPerTokenRoundedUp) {
  ms::ReplyFileResponder r({"héllo"});  // 5 characters (6 bytes)
  const ms::ResponderReply reply = r.respond(kRequest);
  EXPECT_EQ(reply.usage["prompt_tokens"], 3);      // 10 characters
  EXPECT_EQ(reply.usage["completion_tokens"], 2);  // 5 characters
  EXPECT_EQ(reply.usage["total_tokens"], 5);
  EXPECT_FALSE(reply.latency_s.has_value());
  EXPECT_EQ(ms::estimate_tokens(0), 0);
  EXPECT_EQ(ms::estimate_tokens(4), 1);
  EXPECT_EQ(ms::estimate_tokens(5), 2);
}

TEST(ReplyFileResponder, UnusableInputIsNamed) {
  ms::ReplyFileResponderOptions none;
  EXPECT_THROW(ms::make_reply_file_responder(none), std::invalid_argument);
  ms::ReplyFileResponderOptions missing;
  missing.files = {"/nonexistent/reply.json"};
  try {
    ms::make_reply_file_responder(missing);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/reply.json"), std::string::npos);
  }
  const auto bad = temp_file("bad.bin", std::string("\xff\xfe binary", 9));
  ms::ReplyFileResponderOptions binary;
  binary.files = {bad.string()};
  try {
    ms::make_reply_file_responder(binary);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not UTF-8"), std::string::npos);
  }
  std::filesystem::remove(bad);
}

}  // namespace
