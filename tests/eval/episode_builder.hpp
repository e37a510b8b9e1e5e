// Builds small, valid α³-Bench episodes (nlohmann::json) for tests to mutate: 10 alternating
// turns starting with the agent, one MCP action per agent turn answered by its observation,
// calm URLLC network, success, 4000 tokens.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

namespace a3::test {

inline nlohmann::json make_state(double z_m = 120.0, double battery_pct = 80.0) {
  return {
      {"domain", "uav"},
      {"time_s", 0.0},
      {"env", {{"weather", "clear"}, {"wind_mps", 3.0}, {"wind_dir_deg", 90.0}}},
      {"airspace",
       {{"alt_bounds", {30.0, 400.0}},
        {"geofence", {{{"type", "polygon"}, {"points", {{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}}}}}}},
      {"uav",
       {{"pose", {{"x", 10.0}, {"y", 20.0}, {"z", z_m}, {"yaw", 90.0}}},
        {"speed_mps", 8.0},
        {"energy", {{"battery_pct", battery_pct}}},
        {"sensors", {{"rgb", "ok"}, {"gnss", "ok"}}},
        {"payloads", nlohmann::json::array()}}},
      {"policy", {{"alt_bounds", {30.0, 400.0}}}},
      {"safety_flags", {{"nfz_violation", false}, {"separation_breach", false}}}};
}

inline nlohmann::json make_net(const std::string& slice = "URLLC", double lat_ms = 7.0,
                               double loss_pct = 0.1, double throughput_mbps = 90.0,
                               double edge_load = 0.3) {
  return {{"slice", slice},         {"lat_ms", lat_ms},
          {"jitter_ms", 1.0},       {"loss_pct", loss_pct},
          {"throughput_mbps", throughput_mbps}, {"edge_load", edge_load}};
}

inline nlohmann::json make_mcp(const std::string& name) {
  return {{"type", "mcp"}, {"name", name}, {"args", nlohmann::json::object()}};
}

inline nlohmann::json make_mcp_obs(const std::string& name) {
  return {{"tool", name}, {"result", {{"value", "ack"}}}};
}

inline nlohmann::json make_a2a(const std::string& task) {
  return {{"type", "a2a"}, {"task", task}, {"to", "uav_swarm_agent"}, {"payload", nlohmann::json::object()}};
}

inline nlohmann::json make_a2a_obs(const std::string& task) {
  return {{"task", task}, {"from", "uav_swarm_agent"}, {"status", "ok"}, {"payload", nlohmann::json::object()}};
}

inline nlohmann::json make_episode(int turns = 10) {
  nlohmann::json dialogue = nlohmann::json::array();
  for (int i = 0; i < turns; ++i) {
    const bool agent = i % 2 == 0;
    nlohmann::json turn = {{"turn", i + 1},
                           {"speaker", agent ? "agent" : "user"},
                           {"intent", agent ? "act" : "ask"},
                           {"actions", nlohmann::json::array()},
                           {"obs", nlohmann::json::array()},
                           {"net", make_net()}};
    if (agent) {
      turn["actions"].push_back(make_mcp("read_telemetry"));
      turn["obs"].push_back(make_mcp_obs("read_telemetry"));
    }
    dialogue.push_back(turn);
  }
  return {{"initial_state", make_state()},
          {"dialogue", dialogue},
          {"final_state", make_state()},
          {"success", true},
          {"_meta",
           {{"seed", 42},
            {"ts", 1.7e9},
            {"ts_iso", "2026-01-01T00:00:00Z"},
            {"gen_time_s", 10.0},
            {"attempts_used", 1},
            {"generation_failed", false},
            {"usage", {{"prompt_tokens", 1000}, {"completion_tokens", 3000}, {"total_tokens", 4000}}}}}};
}

// A failure stub as the public corpus writes them.
inline nlohmann::json make_failure_stub() {
  const nlohmann::json state = make_state();
  return {{"initial_state", state},
          {"dialogue", nlohmann::json::array()},
          {"final_state", state},
          {"success", false},
          {"_meta",
           {{"model", "test/model"}, {"error", "all attempts failed"}, {"ts", 1.7e9},
            {"generation_failed", true}}}};
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline void write_json(const std::filesystem::path& path, const nlohmann::json& j) {
  write_text(path, j.dump());
}

// A fresh empty folder under the system temp folder, removed by the destructor.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    path_ = std::filesystem::temp_directory_path() /
            ("a3rig-test-" + tag + "-" + std::to_string(::getpid()) + "-" +
             std::to_string(reinterpret_cast<uintptr_t>(this)));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace a3::test
