// One MCP session, transport-free: JSON-RPC 2.0 requests and notifications in, responses and
// progress notifications out, the methods answered from the live rig (McpRig). Methods:
// initialize (2025-06-18 preferred, 2025-03-26 accepted), ping, tools/list, tools/call (on the
// call worker, in arrival order, with notifications/progress when the request carried
// _meta.progressToken), resources/list, resources/read; notifications/initialized and
// notifications/cancelled. Batches (JSON arrays) only in 2025-03-26 sessions.
#pragma once

#include "agent/mcp/mcp_call_worker.hpp"
#include "agent/mcp/mcp_rig.hpp"

#include <nlohmann/json.hpp>

#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <set>
#include <string>

namespace a3::agent::mcp {

inline constexpr const char* kMcpLatestVersion = "2025-06-18";
inline constexpr const char* kMcpBatchVersion = "2025-03-26";  // the revision that has batches

// True for a protocol revision this server speaks.
bool mcp_version_supported(const std::string& version);

// Sends one outgoing message; called from the handling thread or the call worker, one at a time.
using McpSend = std::function<void(const nlohmann::json& message)>;
using McpLog = std::function<void(const std::string&)>;

class McpProtocol {
 public:
  McpProtocol(McpRig& rig, McpLog log);
  ~McpProtocol();  // shutdown(); waits for the call in progress

  // Handles one message or batch. What it sends for it (progress notifications, then the
  // response, or the batch's array of responses) goes to `send`, now or later from the call
  // worker. Returns true when a response (or batch response) will be sent.
  bool handle(const nlohmann::json& message, const McpSend& send);
  // Parses one text message first; unparseable text is answered with -32700.
  bool handle_text(const std::string& text, const McpSend& send);

  // The negotiated revision; empty before initialize.
  std::string protocol_version() const;
  // Drops queued calls and answers nothing more. Idempotent.
  void shutdown();
  // Answers nothing more, but lets the queued calls run and answer first (the client's input
  // ended; its last calls still happen).
  void finish();

  // True when `message` (or a batch member) is a tools/call that asks for progress: its
  // response may be preceded by notifications.
  static bool wants_progress(const nlohmann::json& message);
  // True when `message` is an initialize request.
  static bool is_initialize(const nlohmann::json& message);

 private:
  struct Replies {
    McpSend notify;   // progress notifications
    McpSend respond;  // the one response
  };
  bool handle_batch(const nlohmann::json& batch, const McpSend& send);
  bool handle_one(const nlohmann::json& message, const Replies& replies);
  void handle_notification(const nlohmann::json& message);
  // Answers a request now (returns its result) or queues it (tools/call: returns null).
  nlohmann::json dispatch(const nlohmann::json& request, const Replies& replies);
  nlohmann::json on_initialize(const nlohmann::json& params);
  nlohmann::json on_tools_call(const nlohmann::json& request, const Replies& replies);
  nlohmann::json on_resources_read(const nlohmann::json& params) const;
  nlohmann::json resources_list() const;
  void run_call(const nlohmann::json& id, const std::string& name, const nlohmann::json& arguments,
                const nlohmann::json& progress_token, const Replies& replies);
  bool known_tool(const std::string& name);

  McpRig& rig_;
  McpLog log_;
  mutable std::mutex mutex_;
  std::string version_;
  std::optional<std::set<std::string>> tool_names_;  // tools/list does not change (listChanged false)
  std::atomic<bool> stopped_{false};
  McpCallWorker worker_;
};

}  // namespace a3::agent::mcp
