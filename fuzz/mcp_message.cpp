// Fuzz target "mcp_message": an MCP client's messages, one per input line, through one
// protocol session (JSON-RPC shapes, initialize and version negotiation, batches, tools/call on
// the call worker with progress, resources, notifications), served by a rig that answers at
// once. Invariant: after the session finishes, every message handle_text() promised an answer
// for got exactly one (nothing lost, nothing answered twice).
#include <atomic>
#include <string>

#include "agent/mcp/mcp_protocol.hpp"
#include "agent/tool_catalog.hpp"
#include "fuzz/fuzz_target.hpp"
#include "fuzz/input_reader.hpp"

namespace {

namespace mcp = a3::agent::mcp;

// A vehicle that answers every call at once, with one progress notification.
class InstantRig final : public mcp::McpRig {
 public:
  std::string server_name() const override { return "fuzz-rig"; }
  std::string server_version() const override { return "0"; }
  std::string instructions() const override { return "Survey field A and land."; }
  nlohmann::json tools() const override { return a3::agent::ToolCatalog::builtin().mcp_tools(); }
  std::vector<mcp::McpResource> resources() const override {
    return {mcp::McpResource{"a3rig://mission", "mission", "the mission brief"}};
  }
  std::optional<std::string> read_resource(const std::string& uri) const override {
    if (uri == "a3rig://mission") return std::string(R"({"objective":"survey"})");
    return std::nullopt;
  }
  mcp::McpCallResult call_tool(const std::string& name, const nlohmann::json& arguments,
                               const mcp::McpProgress& progress) override {
    if (progress) progress(0.5, 1.0, "half way");
    return mcp::McpCallResult{{{"tool", name}, {"arguments", arguments}}, "", name == "land"};
  }
  void client_closed() override { closed_ = true; }
  bool episode_over() const override { return closed_; }

 private:
  std::atomic<bool> closed_{false};
};

bool is_answer(const nlohmann::json& message) {
  return message.is_array() || (message.is_object() && !message.contains("method"));
}

}  // namespace

A3_FUZZ_TARGET(mcp_message) {
  static InstantRig rig;
  std::atomic<int> answers{0};
  int promised = 0;
  {
    mcp::McpProtocol protocol(rig, [](const std::string&) {});
    const mcp::McpSend send = [&answers](const nlohmann::json& message) {
      (void)message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
      if (is_answer(message)) ++answers;
    };
    a3::fuzz::InputReader in(input);
    while (!in.empty()) {
      if (protocol.handle_text(in.line(), send)) ++promised;
    }
    protocol.finish();
  }
  a3::fuzz::require(answers.load() == promised, "an MCP request answered not exactly once");
}
