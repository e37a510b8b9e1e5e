// The reference agent's recovery (issue 35): a capture the link lost, or one the sensor refused,
// is not claimed (the agent flies back to the point and takes it again); a take-off the link lost
// is sent again; a sensor activation lost before a survey is sent again with the survey; with
// traffic about, every turn in the air checks the way ahead with the swarm. The
// dialogue of a flown built-in scenario is shown to a fresh scripted agent turn by turn, with the
// answer that matters replaced, and the agent's next decision is read; and parcel-delivery is
// flown whole through a link that loses every message while the launch command crosses it.
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>

#include "agent/conversation/scripted_agent.hpp"
#include "rigs/scenario/builtin_scenarios.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

agent::Turn turn_of(const json& t, const json& rig_turn) {
  agent::Turn turn;
  turn.number = t["turn"].get<int>();
  turn.speaker = t["speaker"].get<std::string>();
  turn.intent = t.value("intent", "");
  turn.text = rig_turn.value("text", "");  // the words are kept in _rig.turns
  turn.actions = t.value("actions", json::array());
  turn.obs = t.value("obs", json::array());
  turn.net = t.value("net", json::object());
  return turn;
}

// The episode's dialogue as the agent was shown it.
std::vector<agent::Turn> dialogue_of(const json& episode) {
  std::vector<agent::Turn> dialogue;
  for (std::size_t i = 0; i < episode["dialogue"].size(); ++i) {
    dialogue.push_back(turn_of(episode["dialogue"][i], episode["_rig"]["turns"][i]));
  }
  return dialogue;
}

// The index of the first agent turn that captured an image and moved on in the same turn.
std::size_t first_capture_turn(const json& dialogue) {
  for (std::size_t i = 0; i < dialogue.size(); ++i) {
    bool capture = false, motion = false;
    for (const auto& a : dialogue[i]["actions"]) {
      capture = capture || a.value("name", "") == "capture_image";
      motion = motion || a.value("name", "") == "set_waypoint";
    }
    if (capture && motion) return i;
  }
  return dialogue.size();
}

// The index of the first turn with an action named `name`.
std::size_t first_turn_with(const std::vector<agent::Turn>& dialogue, const std::string& name) {
  for (std::size_t i = 0; i < dialogue.size(); ++i) {
    for (const auto& a : dialogue[i].actions) {
      if (a.value("name", "") == name) return i;
    }
  }
  return dialogue.size();
}

// Replaces the answer to every action named `name` in `turn`.
void replace_answer(agent::Turn* turn, const std::string& name, const json& result) {
  for (std::size_t i = 0; i < turn->actions.size() && i < turn->obs.size(); ++i) {
    if (turn->actions[i].value("name", "") == name) turn->obs[i] = {{"tool", name}, {"result", result}};
  }
}

std::vector<std::string> names_of(const json& actions) {
  std::vector<std::string> names;
  for (const auto& a : actions) names.push_back(a.value("name", a.value("task", "")));
  return names;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

struct Flown {
  std::vector<agent::Turn> dialogue;
  RigConfigs configs;
};

Flown fly(const std::string& scenario) {
  RunOptions o = a3::test::virtual_run(scenario, "recovery-" + scenario);
  const RunResult r = a3::test::run(o);
  EXPECT_EQ(r.status, "completed");
  EXPECT_EQ(r.episode["_rig"]["agent_faults"], json::array()) << "the reference agent made a fault as flown";
  Flown flown{{}, make_rig_configs(load_scenario(scenario, a3::test::shared_dir()), o)};
  flown.dialogue = dialogue_of(r.episode);
  return flown;
}

// Shows `dialogue` up to (not including) index `until` to a fresh agent, deciding each agent turn
// as the rig would; returns the decision for the turn at `until`.
// `last_max_turns` > 0: the turn budget the last decision sees (as if the dialogue were shorter).
agent::AgentDecision decide_after(const agent::ConversationConfig& conversation, const std::vector<agent::Turn>& dialogue,
                                  std::size_t until, int last_max_turns = 0) {
  const agent::ToolCatalog& tools = agent::ToolCatalog::builtin();
  agent::ScriptedAgent scripted;
  std::vector<agent::Turn> shown;
  agent::AgentDecision last;
  for (std::size_t i = 0; i <= until; ++i) {
    if (dialogue[i].speaker == "agent") {
      agent::AgentContext c;
      c.mission = &conversation.mission;
      c.initial_state = conversation.initial_state;
      c.airspace = conversation.airspace_brief;
      c.dialogue = &shown;
      c.tools = &tools;
      c.net = dialogue[i].net;
      c.turn_number = dialogue[i].number;
      c.max_turns = i == until && last_max_turns > 0 ? last_max_turns : conversation.max_turns;
      last = scripted.decide(c);
    }
    if (i < until) shown.push_back(dialogue[i]);
  }
  return last;
}

TEST(ScriptedAgentRecovery, ACaptureThatTimedOutIsTakenAgainAtThePoint) {
  RunOptions o = a3::test::virtual_run("bridge-inspection", "recovery-capture");
  const RunResult r = a3::test::run(o);
  ASSERT_EQ(r.status, "completed");
  const json& recorded = r.episode["dialogue"];
  const std::size_t capture = first_capture_turn(recorded);
  ASSERT_LT(capture + 2, recorded.size()) << "bridge-inspection no longer captures pier-1 with the next leg";
  std::vector<agent::Turn> dialogue = dialogue_of(r.episode);
  const RigConfigs configs = make_rig_configs(load_scenario("bridge-inspection", a3::test::shared_dir()), o);

  // As flown: the capture stood, so the next agent turn goes on (no flight back to pier-1).
  const agent::AgentDecision as_flown = decide_after(configs.conversation, dialogue, capture + 2);
  EXPECT_EQ(as_flown.text.find("take it again"), std::string::npos) << as_flown.text;

  // The capture's answer lost on the link, but the supervisor confirms pier-1 done: it stands.
  replace_answer(&dialogue[capture], "capture_image", {{"status", "timeout"}});
  ASSERT_EQ(dialogue[capture + 1].intent, "acknowledge_progress") << "the supervisor no longer confirms the capture";
  const agent::AgentDecision confirmed = decide_after(configs.conversation, dialogue, capture + 2);
  EXPECT_EQ(confirmed.text.find("take it again"), std::string::npos) << confirmed.text;

  // Lost, and no confirmation (the supervisor only asks for status): the next agent turn flies
  // back to pier-1 to retake it.
  dialogue[capture + 1].intent = "request_status";
  dialogue[capture + 1].text = "Status report, please.";
  const agent::AgentDecision retake = decide_after(configs.conversation, dialogue, capture + 2);
  EXPECT_NE(retake.text.find("capture_image timed out"), std::string::npos) << retake.text;
  const Eigen::Vector2d pier = configs.conversation.mission.objectives.front().point;
  bool back_to_pier = false;
  for (const auto& a : retake.actions) {
    if (a.value("name", "") != "set_waypoint") continue;
    back_to_pier = std::abs(a["args"]["x"].get<double>() - pier.x()) < 1e-6 && std::abs(a["args"]["y"].get<double>() - pier.y()) < 1e-6;
  }
  EXPECT_TRUE(back_to_pier) << retake.actions.dump();

  // And an error answer (the sensor not active) is treated the same way.
  for (std::size_t i = 0; i < dialogue[capture].actions.size(); ++i) {
    if (dialogue[capture].actions[i].value("name", "") == "capture_image") {
      dialogue[capture].obs[i] = {{"tool", "capture_image"}, {"result", {{"status", "error"}, {"error", "rgb is not active"}}}};
    }
  }
  const agent::AgentDecision after_error = decide_after(configs.conversation, dialogue, capture + 2);
  EXPECT_NE(after_error.text.find("rgb is not active"), std::string::npos) << after_error.text;

  // No turn left to take it again: the agent goes home and says pier-1 is not done, not "done".
  const int last_turn = dialogue[capture + 2].number;
  const agent::AgentDecision home = decide_after(configs.conversation, dialogue, capture + 2, last_turn);
  const std::string pier_id = configs.conversation.mission.objectives.front().id;
  EXPECT_EQ(home.text.find("Mission tasks done"), std::string::npos) << home.text;
  EXPECT_NE(home.text.find("not done: " + pier_id), std::string::npos) << home.text;
}

TEST(ScriptedAgentRecovery, ALostTakeOffIsSentAgain) {
  Flown flown = fly("parcel-delivery");
  const std::size_t launch = first_turn_with(flown.dialogue, "takeoff");
  ASSERT_LT(launch + 2, flown.dialogue.size()) << "parcel-delivery no longer takes off in a turn of its own";
  ASSERT_EQ(first_turn_with({flown.dialogue.begin() + launch + 1, flown.dialogue.end()}, "takeoff"),
            flown.dialogue.size() - launch - 1) << "parcel-delivery took off twice as flown";

  // As flown: the take-off stood, and is not sent again.
  const agent::AgentDecision as_flown = decide_after(flown.configs.conversation, flown.dialogue, launch + 2);
  EXPECT_FALSE(has(names_of(as_flown.actions), "takeoff")) << as_flown.actions.dump();

  // The take-off lost on the link; the supervisor's telemetry shows the vehicle disarmed at home:
  // the next agent turn takes off again and flies the leg.
  replace_answer(&flown.dialogue[launch], "takeoff", {{"status", "timeout"}});
  agent::Turn& supervisor = flown.dialogue[launch + 1];
  ASSERT_TRUE(has(names_of(supervisor.actions), "read_telemetry")) << "the supervisor no longer reads telemetry";
  const agent::Turn as_read = supervisor;
  replace_answer(&supervisor, "read_telemetry",
                 {{"status", "ok"}, {"mode", "disarmed"}, {"armed", false}, {"speed_mps", 0.0},
                  {"pose", {{"x", 100.0}, {"y", 100.0}, {"z", 0.0}}}});
  const agent::AgentDecision again = decide_after(flown.configs.conversation, flown.dialogue, launch + 2);
  const std::vector<std::string> names = names_of(again.actions);
  EXPECT_TRUE(has(names, "takeoff")) << again.actions.dump();
  EXPECT_TRUE(has(names, "navigate_to")) << again.actions.dump();

  // The take-off's answer lost but the telemetry since shows the vehicle armed in the air: it took off.
  supervisor = as_read;
  const agent::AgentDecision airborne = decide_after(flown.configs.conversation, flown.dialogue, launch + 2);
  EXPECT_FALSE(has(names_of(airborne.actions), "takeoff")) << airborne.actions.dump();
}

// parcel-delivery with a replayed network trace that loses every message from mission second 4 to
// 8 (the launch turn is at 5 s), written into `dir`; returns the scenario file.
std::filesystem::path blackout_at_launch(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  json scenario;
  for (const auto& [name, text] : builtin_scenarios()) {
    if (name == "parcel-delivery") scenario = json::parse(text);
  }
  scenario["name"] = "parcel-delivery-blackout";
  scenario["network"] = {{"initial_slice", "URLLC"}, {"trace", "blackout.json"}};
  const json good = {{"slice", "URLLC"}, {"lat_ms", 5}, {"jitter_ms", 1}, {"loss_pct", 0}, {"throughput_mbps", 100}, {"edge_load", 0.3}};
  json lost = good;
  lost["loss_pct"] = 100;
  json trace = json::array({good, lost, good});
  trace[0]["t_s"] = 0;
  trace[1]["t_s"] = 4;
  trace[2]["t_s"] = 8;
  std::ofstream(dir / "blackout.json") << trace.dump();
  std::ofstream(dir / "scenario.json") << scenario.dump(1);
  return dir / "scenario.json";
}

TEST(ScriptedAgentRecovery, ALaunchLostOnTheLinkIsFlownAgainAndTheMissionSucceeds) {
  RunOptions o = a3::test::virtual_run("x", "recovery-blackout");
  o.scenario = blackout_at_launch(o.out_dir / "scenario").string();
  const RunResult r = a3::test::run(o);
  const std::vector<agent::Turn> dialogue = dialogue_of(r.episode);
  const std::size_t launch = first_turn_with(dialogue, "takeoff");
  ASSERT_LT(launch, dialogue.size());
  ASSERT_EQ(dialogue[launch].obs[0]["result"]["status"], "timeout") << "the blackout no longer covers the launch turn";
  // The take-off is sent again in a later turn, and this time it stands.
  const std::size_t again = first_turn_with({dialogue.begin() + launch + 1, dialogue.end()}, "takeoff") + launch + 1;
  ASSERT_LT(again, dialogue.size()) << r.episode["dialogue"].dump();
  EXPECT_EQ(dialogue[again].obs[0]["result"]["status"], "accepted");
  EXPECT_EQ(r.status, "completed");
  EXPECT_TRUE(r.episode["success"].get<bool>());
  EXPECT_EQ(r.episode["_rig"]["agent_faults"], json::array());
}

TEST(ScriptedAgentRecovery, ALostSensorActivationIsSentAgainWithTheSearch) {
  Flown flown = fly("thermal-search");
  const std::size_t search = first_turn_with(flown.dialogue, "execute_maneuver");
  ASSERT_LT(search + 2, flown.dialogue.size()) << "thermal-search no longer searches before its last turn";
  ASSERT_TRUE(has(names_of(flown.dialogue[search].actions), "activate_sensor"));

  // The activation lost on the link, so the search was refused for want of the sensor: both are sent again.
  replace_answer(&flown.dialogue[search], "activate_sensor", {{"status", "timeout"}});
  replace_answer(&flown.dialogue[search], "execute_maneuver",
                 {{"status", "error"}, {"error", "args/sensor: thermal is not active (activate_sensor first)"}});
  const agent::AgentDecision again = decide_after(flown.configs.conversation, flown.dialogue, search + 2);
  const std::vector<std::string> names = names_of(again.actions);
  EXPECT_TRUE(has(names, "activate_sensor")) << again.actions.dump();
  EXPECT_TRUE(has(names, "execute_maneuver")) << again.actions.dump();
  EXPECT_NE(again.text.find("activate_sensor timed out"), std::string::npos) << again.text;
}

// With traffic about, every turn from the launch to the landing checks the way ahead with the
// swarm (after the motion where it sends one, so the swarm predicts along the new route); without
// traffic, never.
TEST(ScriptedAgentRecovery, WithTrafficAboutEveryTurnInTheAirChecksTheWayAheadWithTheSwarm) {
  const std::vector<std::string> motions = {"takeoff", "navigate_to", "set_waypoint", "execute_maneuver",
                                            "return_to_home"};
  const Flown traffic = fly("traffic-conflict");
  const std::size_t launch = first_turn_with(traffic.dialogue, "takeoff");
  ASSERT_LT(launch, traffic.dialogue.size());
  bool landed = false;
  int checks = 0;
  for (std::size_t i = launch; i < traffic.dialogue.size(); ++i) {
    const agent::Turn& t = traffic.dialogue[i];
    landed = landed || t.intent == "acknowledge_landing";
    if (t.speaker != "agent") continue;
    const std::vector<std::string> names = names_of(t.actions);
    const auto ask = std::find(names.begin(), names.end(), "collision_avoidance");
    EXPECT_EQ(ask != names.end(), !landed) << "turn " << t.number << " (" << t.intent << "): " << t.actions.dump();
    for (const std::string& motion : motions) {
      const auto sent = std::find(names.begin(), names.end(), motion);
      if (sent != names.end()) {
        EXPECT_TRUE(ask > sent) << "turn " << t.number << ": " << t.actions.dump();
      }
    }
    checks += ask != names.end() ? 1 : 0;
  }
  EXPECT_GE(checks, 3);
  std::cout << "traffic-conflict: " << checks << " turns in the air checked with the swarm\n";

  const Flown quiet = fly("parcel-delivery");
  for (const agent::Turn& t : quiet.dialogue) {
    EXPECT_FALSE(has(names_of(t.actions), "collision_avoidance")) << "turn " << t.number << ": " << t.actions.dump();
  }
}

}  // namespace
}  // namespace a3::rigs
