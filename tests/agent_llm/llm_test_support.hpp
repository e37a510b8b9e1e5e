// Helpers of the llm agent tests: agent contexts from the built-in scenarios with a dialogue
// played out by the scripted agent against synthetic observations, and a fake OpenAI-compatible
// server (cpp-httplib on 127.0.0.1) that answers from a queue and records what it was sent.
#pragma once

#include <httplib.h>

#include <gtest/gtest.h>

#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "agent/conversation/scripted_agent.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/test_support.hpp"

namespace a3::test {

// An observation the vehicle side could have sent for an action (only the fields the policy and
// the prompt use). `flying` makes read_telemetry report a route being flown.
inline nlohmann::json synthetic_observation(const nlohmann::json& action, bool flying) {
  if (action.value("type", "") == "a2a") {
    nlohmann::json payload = {{"ok", true}};
    if (action.value("task", "") == "path_plan") {
      payload = {{"waypoints", {{150.0, 220.0, 60.0}, {560.0, 210.0, 60.0}}}, {"length_m", 612.5}};
    }
    return {{"task", action["task"]}, {"from", action["to"]}, {"status", "ok"}, {"payload", payload}};
  }
  const std::string name = action.value("name", "");
  if (name == "read_telemetry") {
    nlohmann::json r = {{"status", "ok"},
                        {"pose", {{"x", 12.5}, {"y", -3.25}, {"z", 59.75}, {"yaw", 90.0}}},
                        {"speed_mps", flying ? 7.9 : 0.1},
                        {"battery_pct", 93.4},
                        {"mode", flying ? "goto" : "hold"}};
    if (flying) r["route"] = {{"index", 1}, {"of", 3}};
    return {{"tool", name}, {"result", r}};
  }
  return {{"tool", name}, {"result", {{"status", "ok"}, {"accepted", true}}}};
}

inline nlohmann::json normal_net() {
  return {{"slice", "eMBB"}, {"lat_ms", 14.25}, {"jitter_ms", 3.5}, {"loss_pct", 0.25},
          {"throughput_mbps", 612.0}, {"edge_load", 0.41}};
}

inline nlohmann::json hard_net() {
  return {{"slice", "mMTC"}, {"lat_ms", 95.5}, {"jitter_ms", 20.0}, {"loss_pct", 2.5},
          {"throughput_mbps", 2.1}, {"edge_load", 0.85}};
}

// A scenario's context at some turn, its dialogue played by a live scripted agent.
struct PlayedContext {
  rigs::Scenario scenario;
  std::vector<agent::Turn> dialogue;
  nlohmann::json telemetry;
  // The decisions the live agent made, per agent turn, in order.
  std::vector<agent::AgentDecision> decisions;

  agent::AgentContext context(int turn_number, const nlohmann::json& net) const {
    agent::AgentContext c;
    c.mission = &scenario.mission;
    c.initial_state = scenario.initial_state;
    c.airspace = scenario.airspace_brief();
    c.dialogue = &dialogue;
    c.tools = &agent::ToolCatalog::builtin();
    c.net = net;
    c.last_telemetry = telemetry;
    c.turn_number = turn_number;
    c.max_turns = 12;
    c.mission_time_s = 10.0 * turn_number + 0.125;
    return c;
  }
};

// Plays `turns` turns (agent on odd ones): the agent decides live; the supervisor says something
// (a traffic alert at turn `alert_turn`); the network is hard on the turns listed in `hard`.
inline PlayedContext play_scripted(const std::string& scenario_name, int turns, int alert_turn = -1,
                                   std::vector<int> hard = {}) {
  PlayedContext p{rigs::load_scenario_spec(scenario_name, shared_dir()), {}, nullptr, {}};
  agent::ScriptedAgent live;
  for (int k = 1; k <= turns; ++k) {
    const bool is_hard = std::find(hard.begin(), hard.end(), k) != hard.end();
    const nlohmann::json net = is_hard ? hard_net() : normal_net();
    agent::Turn t;
    t.number = k;
    t.net = net;
    t.started_s = 10.0 * k + 0.125;
    if (k % 2 == 1) {
      agent::AgentDecision d = live.decide(p.context(k, net));
      t.speaker = "agent";
      t.intent = d.intent;
      t.text = d.text;
      t.actions = d.actions;
      p.decisions.push_back(d);
    } else {
      t.speaker = "user";
      t.intent = k == alert_turn ? "traffic_alert" : "acknowledge";
      t.text = k == alert_turn ? "Traffic: peer-1 at 85 m, closing." : "Understood, carry on.";
      if (k == 4) t.actions.push_back({{"type", "mcp"}, {"name", "read_telemetry"}, {"args", nlohmann::json::object()}});
    }
    t.obs = nlohmann::json::array();
    for (const auto& a : t.actions) {
      t.obs.push_back(synthetic_observation(a, k % 4 == 3));
      if (a.value("name", "") == "read_telemetry") p.telemetry = t.obs.back()["result"];
    }
    p.dialogue.push_back(t);
  }
  return p;
}

// An OpenAI chat-completions response body.
inline std::string completion_body(const std::string& content, int prompt_tokens = 100, int completion_tokens = 20,
                                   const std::string& finish_reason = "stop") {
  return nlohmann::json({{"id", "chatcmpl-test"},
                         {"object", "chat.completion"},
                         {"model", "fake-model"},
                         {"choices", {{{"index", 0},
                                       {"message", {{"role", "assistant"}, {"content", content}}},
                                       {"finish_reason", finish_reason}}}},
                         {"usage", {{"prompt_tokens", prompt_tokens},
                                    {"completion_tokens", completion_tokens},
                                    {"total_tokens", prompt_tokens + completion_tokens}}}})
      .dump();
}

// A fake model on 127.0.0.1: each POST /v1/chat/completions gets the next queued answer
// (status, body); the request bodies and Authorization headers are kept.
class FakeChatServer {
 public:
  struct Answer {
    int status = 200;
    std::string body;
  };
  FakeChatServer() {
    server_.Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) {
      std::lock_guard<std::mutex> lock(mutex_);
      requests_.push_back(nlohmann::json::parse(req.body, nullptr, false));
      authorizations_.push_back(req.get_header_value("Authorization"));
      Answer a{500, R"({"error": {"message": "fake server: no answer queued"}})"};
      if (!answers_.empty()) {
        a = answers_.front();
        answers_.pop_front();
      }
      res.status = a.status;
      res.set_content(a.body, "application/json");
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~FakeChatServer() {
    server_.stop();
    thread_.join();
  }
  void reply(const std::string& content, int prompt_tokens = 100, int completion_tokens = 20) {
    std::lock_guard<std::mutex> lock(mutex_);
    answers_.push_back({200, completion_body(content, prompt_tokens, completion_tokens)});
  }
  void fail(int status, const std::string& body) {
    std::lock_guard<std::mutex> lock(mutex_);
    answers_.push_back({status, body});
  }
  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }
  std::vector<nlohmann::json> requests() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return requests_;
  }
  std::vector<std::string> authorizations() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return authorizations_;
  }

 private:
  httplib::Server server_;
  std::thread thread_;
  int port_ = 0;
  mutable std::mutex mutex_;
  std::deque<Answer> answers_;
  std::vector<nlohmann::json> requests_;
  std::vector<std::string> authorizations_;
};

}  // namespace a3::test
