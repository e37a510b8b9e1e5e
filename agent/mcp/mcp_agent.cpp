// The rendezvous between an MCP client's calls and the conversation's agent turns.
#include "agent/mcp/mcp_agent.hpp"

#include <cstdio>

namespace a3::agent::mcp {
namespace {

constexpr auto kStopPoll = std::chrono::milliseconds(100);

// Forwards to an McpAgent that outlives it (the conversation owns this one).
class BorrowedAgent final : public Agent {
 public:
  explicit BorrowedAgent(McpAgent& agent) : agent_(agent) {}
  std::string name() const override { return agent_.name(); }
  AgentDecision decide(const AgentContext& context) override { return agent_.decide(context); }
  void on_mission_time(double t) override { agent_.on_mission_time(t); }
  void on_dialogue(const std::vector<Turn>& d, bool over, const std::string& why) override {
    agent_.on_dialogue(d, over, why);
  }
  void stop_deciding() override { agent_.stop_deciding(); }

 private:
  McpAgent& agent_;
};

McpCallResult dialogue_over_result(const std::string& why) {
  return error_result("dialogue_over", "the dialogue is over (" + why +
                                           "): no more turns; the episode is written when the vehicle has landed");
}

}  // namespace

McpAgent::McpAgent(McpMissionBrief brief, McpAgentOptions options, const ToolCatalog& catalog)
    : brief_(std::move(brief)), options_(options), catalog_(catalog) {}

McpAgent::~McpAgent() { stop_deciding(); }

std::unique_ptr<Agent> McpAgent::borrow() { return std::make_unique<BorrowedAgent>(*this); }

bool McpAgent::stopping() const { return torn_down_ || (options_.stop != nullptr && options_.stop->load()); }

void McpAgent::answer(McpCallResult result) {
  result_ = std::move(result);
  phase_ = Phase::kIdle;
  changed_.notify_all();
}

// ---- The conversation's side ----

AgentDecision McpAgent::decide(const AgentContext& context) {
  std::unique_lock<std::mutex> lock(mutex_);
  mission_time_s_ = context.mission_time_s;
  hand_over_result(context);
  const auto waiting_since = SteadyClock::now();
  while (phase_ != Phase::kPosted && !stopping()) changed_.wait_for(lock, kStopPoll);
  if (phase_ != Phase::kPosted) {
    AgentDecision d;
    d.intent = "session_closed";
    d.text = "The MCP client's session has ended.";
    return d;
  }
  return take_call(waiting_since);
}

// The result of the call in hand, from what the conversation now knows.
void McpAgent::hand_over_result(const AgentContext& c) {
  if (phase_ == Phase::kAwaitObservation) {
    if (c.step > 1 && !c.turn_obs.empty()) {
      answer(observation_result(c.turn_actions.back(), c.turn_obs.back()));
    } else {
      answer(error_result("lost", "the call's turn ended before its observation came back"));
    }
  } else if (phase_ == Phase::kAwaitReply) {
    if (c.dialogue != nullptr && !c.dialogue->empty() && c.dialogue->back().speaker == "user") {
      answer(supervisor_reply_result(c.dialogue->back(), brief_.max_turns, false, ""));
    } else {
      answer(error_result("lost", "the supervisor's reply is missing from the dialogue"));
    }
  }
}

AgentDecision McpAgent::take_call(SteadyClock::time_point waiting_since) {
  AgentDecision d;
  if (options_.charge_wall_time) d.latency_s = std::chrono::duration<double>(SteadyClock::now() - waiting_since).count();
  if (posted_.ends_turn) {
    d.intent = posted_.action.value("intent", "");
    d.text = posted_.action.value("text", "");
    phase_ = Phase::kAwaitReply;
  } else {
    d.actions = nlohmann::json::array({posted_.action});
    d.turn_continues = true;
    phase_ = Phase::kAwaitObservation;
  }
  return d;
}

void McpAgent::on_mission_time(double mission_time_s) {
  std::lock_guard<std::mutex> lock(mutex_);
  mission_time_s_ = mission_time_s;
}

void McpAgent::on_dialogue(const std::vector<Turn>& dialogue, bool over, const std::string& why) {
  std::lock_guard<std::mutex> lock(mutex_);
  dialogue_ = dialogue;
  if (!dialogue.empty()) mission_time_s_ = std::max(mission_time_s_, dialogue.back().finished_s);
  if (!over) return;
  dialogue_over_ = true;
  dialogue_end_reason_ = why;
  if (phase_ == Phase::kAwaitReply) {
    if (!dialogue.empty() && dialogue.back().speaker == "user") {
      answer(supervisor_reply_result(dialogue.back(), brief_.max_turns, true, why));
    } else {
      McpCallResult r;  // the agent's turn was the last one
      r.structured = {{"dialogue_over", true}, {"reason", why}};
      answer(r);
    }
  } else if (phase_ != Phase::kIdle) {
    answer(dialogue_over_result(why));
  }
}

void McpAgent::stop_deciding() {
  std::lock_guard<std::mutex> lock(mutex_);
  torn_down_ = true;
  changed_.notify_all();
}

// ---- The MCP server's side ----

std::vector<McpResource> McpAgent::resources() const {
  return {{"a3rig://mission", "mission", "The mission brief: objectives, airspace, initial state, turn budget"},
          {"a3rig://dialogue", "dialogue", "The dialogue so far: every turn with its actions, observations and n_t"}};
}

std::optional<std::string> McpAgent::read_resource(const std::string& uri) const {
  if (uri == "a3rig://mission") return mission_resource_json(brief_).dump(2);
  if (uri == "a3rig://dialogue") {
    std::lock_guard<std::mutex> lock(mutex_);
    return dialogue_json(dialogue_, dialogue_over_, dialogue_end_reason_).dump(2);
  }
  return std::nullopt;
}

std::optional<McpCallResult> McpAgent::answer_without_step(const CallAsAction& call) {
  if (episode_over_) {
    return error_result("episode_over", "the episode is over (status " + episode_status_ + "); written to " +
                                            episode_path_.string());
  }
  if (!call.problem.empty()) return error_result("bad_call", call.problem);
  if (dialogue_over_) return dialogue_over_result(dialogue_end_reason_);
  if (client_closed_ || stopping()) return error_result("stopping", "the run is stopping; the episode is being written");
  return std::nullopt;
}

std::string McpAgent::waiting_for() const {
  char prefix[64];
  std::snprintf(prefix, sizeof prefix, "mission time %.1f s: ", mission_time_s_);
  switch (phase_) {
    case Phase::kPosted: return prefix + std::string("waiting for the agent's turn to begin");
    case Phase::kAwaitObservation:
      return prefix + ToolCatalog::function_name_of(posted_.action) + " crossing the link and executing on the vehicle";
    case Phase::kAwaitReply:
      return prefix + std::string("waiting for the supervisor's reply (it comes when the vehicle has settled, an "
                                  "objective is done, the link degrades or traffic comes close)");
    case Phase::kIdle: break;
  }
  return prefix + std::string("waiting");
}

McpCallResult McpAgent::call_tool(const std::string& name, const nlohmann::json& arguments,
                                  const McpProgress& progress) {
  std::lock_guard<std::mutex> serial(call_mutex_);
  const CallAsAction call = catalog_.action_from_call(name, arguments);
  std::unique_lock<std::mutex> lock(mutex_);
  if (auto early = answer_without_step(call)) return *early;
  posted_ = call;
  result_.reset();
  phase_ = Phase::kPosted;
  changed_.notify_all();
  const auto period = std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(options_.progress_period_s));
  auto next_progress = SteadyClock::now() + period;
  int reports = 0;
  while (!result_) {
    changed_.wait_until(lock, std::min(next_progress, SteadyClock::now() + kStopPoll));
    if (result_) break;
    if (episode_over_ || stopping() || client_closed_) {
      const auto why = answer_without_step(CallAsAction{});
      answer(why ? *why : error_result("stopping", "the run has ended; the episode is being written"));
      break;
    }
    if (SteadyClock::now() >= next_progress && progress) {
      next_progress += period;
      const std::string message = waiting_for();
      lock.unlock();
      progress(++reports, std::nullopt, message);
      lock.lock();
    }
  }
  McpCallResult r = std::move(*result_);
  result_.reset();
  return r;
}

void McpAgent::client_closed() {
  std::lock_guard<std::mutex> lock(mutex_);
  client_closed_ = true;
  if (!dialogue_over_ && options_.stop != nullptr) options_.stop->store(true);
  changed_.notify_all();
}

bool McpAgent::episode_over() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return episode_over_;
}

bool McpAgent::client_gone() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return client_closed_;
}

bool McpAgent::dialogue_over() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dialogue_over_;
}

void McpAgent::set_episode_over(const std::string& status, const std::filesystem::path& episode) {
  std::lock_guard<std::mutex> lock(mutex_);
  episode_over_ = true;
  episode_status_ = status;
  episode_path_ = episode;
  changed_.notify_all();
}

}  // namespace a3::agent::mcp
