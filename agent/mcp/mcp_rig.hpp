// What the MCP server (mcp_server.hpp: JSON-RPC over stdio or Streamable HTTP) asks of the live
// rig. The protocol layer knows nothing of vehicles or episodes; the rig side (mcp_agent.hpp,
// behind `a3rig mcp`) knows nothing of JSON-RPC. Calls may come from any thread of the
// transport; an implementation serialises them (a client's calls execute one at a time, in the
// order they came).
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace a3::agent::mcp {

// The result of one tools/call, as MCP's CallToolResult carries it.
struct McpCallResult {
  nlohmann::json structured = nlohmann::json::object();  // structuredContent (an object)
  std::string text;        // content[0].text; empty: the transport uses structured.dump()
  bool is_error = false;   // isError: a refusal by the safety gate, a bad argument, the episode over
};

// A progress notification for a long call: progress rises; total may be unknown.
using McpProgress = std::function<void(double progress, std::optional<double> total, const std::string& message)>;

struct McpResource {
  std::string uri;          // e.g. "a3rig://mission"
  std::string name;
  std::string description;
  std::string mime_type = "application/json";
};

class McpRig {
 public:
  virtual ~McpRig() = default;
  // serverInfo.name / version and the instructions of InitializeResult (the mission brief).
  virtual std::string server_name() const = 0;
  virtual std::string server_version() const = 0;
  virtual std::string instructions() const = 0;
  // tools/list: ToolCatalog::mcp_tools() (every vehicle tool, every A2A task, report_turn).
  virtual nlohmann::json tools() const = 0;
  virtual std::vector<McpResource> resources() const = 0;
  // resources/read: the resource's text, or std::nullopt for an unknown URI.
  virtual std::optional<std::string> read_resource(const std::string& uri) const = 0;
  // tools/call: blocks until the call's observation is back (or the supervisor's reply, for
  // report_turn); `progress` may be called meanwhile from the calling thread. Unknown tools and
  // bad arguments come back as is_error results, never as exceptions.
  virtual McpCallResult call_tool(const std::string& name, const nlohmann::json& arguments,
                                  const McpProgress& progress) = 0;
  // The client went away (stdin closed, HTTP session deleted): the episode ends and is written.
  virtual void client_closed() = 0;
  // True once the episode has been written (calls then answer is_error with its status).
  virtual bool episode_over() const = 0;
};

}  // namespace a3::agent::mcp
