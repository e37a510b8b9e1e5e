// A fake live rig for the MCP protocol tests: three tools (read_telemetry answers at once,
// fly_to reports progress and blocks until the test releases it, report_turn), one resource,
// and a record of every call and of client_closed().
#pragma once

#include "agent/mcp/mcp_rig.hpp"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

namespace a3::agent::mcp::testing {

class FakeMcpRig : public McpRig {
 public:
  std::string server_name() const override { return "fake-rig"; }
  std::string server_version() const override { return "0.0.1"; }
  std::string instructions() const override { return "Fly to the survey area and land."; }
  nlohmann::json tools() const override {
    const nlohmann::json object_schema{{"type", "object"}};
    return nlohmann::json::array({{{"name", "read_telemetry"}, {"inputSchema", object_schema}},
                                  {{"name", "fly_to"}, {"inputSchema", object_schema}},
                                  {{"name", "report_turn"}, {"inputSchema", object_schema}}});
  }
  std::vector<McpResource> resources() const override {
    return {McpResource{"a3rig://mission", "mission", "the mission brief", "application/json"}};
  }
  std::optional<std::string> read_resource(const std::string& uri) const override {
    if (uri == "a3rig://mission") return std::string(R"({"objective":"survey"})");
    return std::nullopt;
  }
  McpCallResult call_tool(const std::string& name, const nlohmann::json& arguments,
                          const McpProgress& progress) override {
    {
      std::lock_guard lock(mutex_);
      calls_.push_back(name);
    }
    if (name == "fly_to") return fly(arguments, progress);
    if (name == "report_turn") return McpCallResult{{{"supervisor", "carry on"}}, "carry on", false};
    if (arguments.contains("fail")) throw std::runtime_error("telemetry bus down");
    return McpCallResult{{{"altitude_m", 12.5}}, "", false};
  }
  void client_closed() override { closed = true; }
  bool episode_over() const override { return closed; }

  // Lets blocked fly_to calls return.
  void release() {
    {
      std::lock_guard lock(mutex_);
      released_ = true;
    }
    cv_.notify_all();
  }
  bool wait_for_flying(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    return cv_.wait_for(lock, timeout, [this] { return flying_; });
  }
  std::vector<std::string> call_log() {
    std::lock_guard lock(mutex_);
    return calls_;
  }

  std::atomic<bool> closed{false};

 private:
  McpCallResult fly(const nlohmann::json& arguments, const McpProgress& progress) {
    progress(0.5, 1.0, "halfway");
    progress(0.5, 1.0, "not rising: dropped");
    std::unique_lock lock(mutex_);
    flying_ = true;
    cv_.notify_all();
    cv_.wait(lock, [this] { return released_; });
    lock.unlock();
    progress(1.0, 1.0, "");
    if (arguments.value("refuse", false)) return McpCallResult{{{"refused", "geofence"}}, "refused: geofence", true};
    return McpCallResult{{{"arrived", true}}, "arrived", false};
  }

  std::mutex mutex_;
  std::condition_variable cv_;
  bool released_ = false;
  bool flying_ = false;
  std::vector<std::string> calls_;
};

}  // namespace a3::agent::mcp::testing
