// Log lines carry text from models and files: control characters never reach the terminal raw.
#include <gtest/gtest.h>

#include <string>

#include "common/log.hpp"

namespace a3::common {
namespace {

TEST(Log, ControlCharactersAreShownEscapedNotSentToTheTerminal) {
  set_log_level(LogLevel::kInfo);
  testing::internal::CaptureStderr();
  log_warn("conversation", std::string("tool '\x1b]0;pwned\x07\x1b[2J' \r unknown\x7f end\0after", 42));
  const std::string line = testing::internal::GetCapturedStderr();
  EXPECT_EQ(line, "[warn] conversation: tool '\\x1b]0;pwned\\x07\\x1b[2J' \\x0d unknown\\x7f end\\x00after\n");
}

TEST(Log, PlainTextIsUnchanged) {
  set_log_level(LogLevel::kInfo);
  testing::internal::CaptureStderr();
  log_info("rig", "turn 3: navigate_to (12.5, -3) → accepted\tok");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "[info] rig: turn 3: navigate_to (12.5, -3) → accepted\tok\n");
}

}  // namespace
}  // namespace a3::common
