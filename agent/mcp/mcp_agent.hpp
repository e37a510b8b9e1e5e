// The agent of `a3rig mcp`: an MCP client's tool calls become the conversation's agent turns.
// It is both the conversation's Agent and the MCP server's McpRig, a rendezvous between the
// transport's thread (call_tool) and the conversation (decide):
// - a vehicle tool or A2A task call (checked with ToolCatalog::action_from_call; a bad one
//   answers is_error at once, without a turn step) is one step of the agent's turn; its result
//   is the step's observation, handed over at the conversation's next decide();
// - report_turn ends the agent's turn (intent, text); its result is the supervisor's reply,
//   handed over when the conversation next asks the agent to decide (or when the dialogue ends).
// Time: in virtual time decide() blocks the simulation while the client thinks, and each step
// is charged the wall time since decide() began waiting (the previous result was handed then),
// unless charge_wall_time is off (a --think-time model is charged instead); in real time the
// conversation runs decide() on a thread and the client's time passes in the world.
// A waiting call reports progress about once a second. Nothing blocks for ever: decide()
// returns when the run's stop flag is set or the conversation is torn down; waiting calls
// return when the dialogue or the episode is over or the run stops.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>

#include "agent/conversation/agent.hpp"
#include "agent/mcp/mcp_brief.hpp"
#include "agent/mcp/mcp_rig.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::agent::mcp {

struct McpAgentOptions {
  // Virtual time: charge each step the client's measured wall time. Off when a --think-time
  // model is charged instead.
  bool charge_wall_time = true;
  // The run's stop flag: set by client_closed() mid-dialogue; decide() returns when it is set.
  std::atomic<bool>* stop = nullptr;
  double progress_period_s = 1.0;
  std::string server_version = "0";
};

class McpAgent final : public Agent, public McpRig {
 public:
  explicit McpAgent(McpMissionBrief brief, McpAgentOptions options = {},
                    const ToolCatalog& catalog = ToolCatalog::builtin());
  ~McpAgent() override;

  // Agent (the conversation's side).
  std::string name() const override { return "mcp"; }
  AgentDecision decide(const AgentContext& context) override;
  void on_mission_time(double mission_time_s) override;
  void on_dialogue(const std::vector<Turn>& dialogue, bool over, const std::string& why) override;
  void stop_deciding() override;

  // McpRig (the MCP server's side).
  std::string server_name() const override { return "a3rig"; }
  std::string server_version() const override { return options_.server_version; }
  std::string instructions() const override { return instructions_text(brief_); }
  nlohmann::json tools() const override { return catalog_.mcp_tools(); }
  std::vector<McpResource> resources() const override;
  std::optional<std::string> read_resource(const std::string& uri) const override;
  McpCallResult call_tool(const std::string& name, const nlohmann::json& arguments,
                          const McpProgress& progress) override;
  void client_closed() override;
  bool episode_over() const override;

  // The rig's side.
  // An Agent for RunOptions::agent_factory that forwards to this one (which must outlive it).
  std::unique_ptr<Agent> borrow();
  // The episode has been written: calls answer is_error naming the status and the file.
  void set_episode_over(const std::string& status, const std::filesystem::path& episode);
  bool client_gone() const;
  bool dialogue_over() const;

 private:
  using SteadyClock = std::chrono::steady_clock;
  // Where the call in hand is.
  enum class Phase { kIdle, kPosted, kAwaitObservation, kAwaitReply };

  bool stopping() const;  // with mutex_ held
  void hand_over_result(const AgentContext& context);
  AgentDecision take_call(SteadyClock::time_point waiting_since);
  std::string waiting_for() const;  // with mutex_ held
  std::optional<McpCallResult> answer_without_step(const CallAsAction& call);  // with mutex_ held
  void answer(McpCallResult result);  // with mutex_ held

  const McpMissionBrief brief_;
  const McpAgentOptions options_;
  const ToolCatalog& catalog_;

  std::mutex call_mutex_;  // one call at a time, in order
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  Phase phase_ = Phase::kIdle;
  CallAsAction posted_;
  std::optional<McpCallResult> result_;
  bool torn_down_ = false;
  bool client_closed_ = false;
  bool dialogue_over_ = false;
  std::string dialogue_end_reason_;
  bool episode_over_ = false;
  std::string episode_status_;
  std::filesystem::path episode_path_;
  double mission_time_s_ = 0.0;
  std::vector<Turn> dialogue_;
};

}  // namespace a3::agent::mcp
