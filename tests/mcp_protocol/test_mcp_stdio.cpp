// MCP's stdio transport: newline-delimited messages in and out, EOF ends the session, stop()
// ends a read blocked on fd 0.
#include "agent/mcp/mcp_server.hpp"
#include "tests/mcp_protocol/fake_mcp_rig.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <future>
#include <iostream>
#include <map>
#include <sstream>

namespace a3::agent::mcp {
namespace {

using nlohmann::json;
using testing::FakeMcpRig;

const char* kInitialize =
    R"({"jsonrpc":"2.0","id":0,"method":"initialize","params":{"protocolVersion":"2025-06-18","capabilities":{},"clientInfo":{"name":"t","version":"1"}}})";

std::vector<json> lines_of(const std::string& text) {
  std::vector<json> messages;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) messages.push_back(json::parse(line));
  return messages;
}

McpServerOptions quiet() {
  McpServerOptions options;
  options.log = [](const std::string&) {};
  return options;
}

TEST(McpStdio, AnswersEachLineOnALineOfItsOwnAndEndsTheSessionAtEof) {
  FakeMcpRig rig;
  std::istringstream in(std::string(kInitialize) + "\n" +
                        R"({"jsonrpc":"2.0","method":"notifications/initialized"})" "\n\n" +
                        R"({"jsonrpc":"2.0","id":1,"method":"tools/call","params":{"name":"read_telemetry","arguments":{}}})" "\r\n" +
                        "not json\n" +
                        R"({"jsonrpc":"2.0","id":2,"method":"ping"})");  // the last line lacks its newline
  std::ostringstream out;
  McpServer server(rig, quiet());
  server.serve_stdio(in, out);
  std::map<std::string, json> by_id;  // the call is answered by the worker, maybe after later lines
  for (const auto& message : lines_of(out.str())) by_id[message["id"].dump()] = message;
  ASSERT_EQ(by_id.size(), 4u);
  EXPECT_EQ(by_id["0"]["result"]["protocolVersion"], "2025-06-18");
  EXPECT_EQ(by_id["1"]["result"]["structuredContent"]["altitude_m"], 12.5);
  EXPECT_EQ(by_id["null"]["error"]["code"], -32700);
  EXPECT_EQ(by_id["2"]["result"], json::object());
  EXPECT_TRUE(rig.closed);
}

TEST(McpStdio, DiagnosticsGoToTheLogNotToTheOutput) {
  FakeMcpRig rig;
  std::istringstream in(std::string(kInitialize) + "\n" + R"({"jsonrpc":"2.0","method":"notifications/unknown"})" "\n");
  std::ostringstream out;
  std::vector<std::string> log;
  McpServerOptions options;
  options.log = [&log](const std::string& line) { log.push_back(line); };
  McpServer server(rig, options);
  server.serve_stdio(in, out);
  EXPECT_EQ(lines_of(out.str()).size(), 1u);
  EXPECT_FALSE(log.empty());
}

TEST(McpStdio, OutputThatCannotBeWrittenEndsTheSessionAsEofDoes) {
  FakeMcpRig rig;
  std::istringstream in(std::string(kInitialize) + "\n" + R"({"jsonrpc":"2.0","id":1,"method":"ping"})" "\n");
  std::ostringstream out;
  out.setstate(std::ios::badbit);  // as std::cout after the client's end of the pipe closed
  std::vector<std::string> log;
  McpServerOptions options;
  options.log = [&log](const std::string& line) { log.push_back(line); };
  McpServer server(rig, options);
  server.serve_stdio(in, out);
  EXPECT_TRUE(rig.closed);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_NE(log[0].find("cannot write to the client"), std::string::npos);
}

// Replaces fd 0 with a pipe for the test's lifetime, so std::cin is a stream the test controls.
class StdinPipe {
 public:
  StdinPipe() {
    saved_ = ::dup(0);
    EXPECT_EQ(::pipe(fds_), 0);
    ::dup2(fds_[0], 0);
  }
  ~StdinPipe() {
    ::close(fds_[1]);
    ::dup2(saved_, 0);
    ::close(saved_);
    ::close(fds_[0]);
  }
  void write_line(const std::string& line) {
    const std::string text = line + "\n";
    EXPECT_EQ(::write(fds_[1], text.data(), text.size()), static_cast<ssize_t>(text.size()));
  }

 private:
  int saved_ = -1;
  int fds_[2] = {-1, -1};
};

TEST(McpStdio, StopEndsAReadBlockedOnStdinWithoutClosingTheSession) {
  FakeMcpRig rig;
  StdinPipe stdin_pipe;
  std::ostringstream out;
  McpServer server(rig, quiet());
  stdin_pipe.write_line(kInitialize);
  auto served = std::async(std::launch::async, [&] { server.serve_stdio(std::cin, out); });
  EXPECT_EQ(served.wait_for(std::chrono::milliseconds(300)), std::future_status::timeout);
  server.stop();
  ASSERT_EQ(served.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_EQ(lines_of(out.str()).size(), 1u);
  EXPECT_FALSE(rig.closed);
}

TEST(McpStdio, APingIsAnsweredWhileACallBlocks) {
  FakeMcpRig rig;
  StdinPipe stdin_pipe;
  std::ostringstream out;
  McpServer server(rig, quiet());
  auto served = std::async(std::launch::async, [&] { server.serve_stdio(std::cin, out); });
  stdin_pipe.write_line(kInitialize);
  stdin_pipe.write_line(R"({"jsonrpc":"2.0","id":1,"method":"tools/call","params":{"name":"fly_to","arguments":{}}})");
  ASSERT_TRUE(rig.wait_for_flying(std::chrono::seconds(10)));
  stdin_pipe.write_line(R"({"jsonrpc":"2.0","id":2,"method":"ping"})");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  rig.release();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  server.stop();
  served.wait();
  const auto messages = lines_of(out.str());
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[1]["id"], 2);  // the ping's answer came before the call's
  EXPECT_EQ(messages[2]["id"], 1);
}

}  // namespace
}  // namespace a3::agent::mcp
