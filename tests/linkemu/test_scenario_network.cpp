// A scenario's network section, parsed once by the link emulator's parser
// (linkemu/scenario_network.hpp): every field read with its default, a relative trace made
// absolute against the scenario's folder (alphabench:<path> kept for the orchestrator), the
// link settings the scenario owns refused inside link, and each bad field refused naming its
// JSON path.
#include <gtest/gtest.h>

#include <string>

#include "common/json_file.hpp"
#include "linkemu/scenario_network.hpp"

namespace a3::linkemu {
namespace {

using nlohmann::json;

const std::string kPath = "s.json: /network";

std::string error_of(const json& network) {
  try {
    (void)parse_scenario_network(network, kPath, "/scenarios");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ScenarioNetworkParser, AnEmptySectionGivesTheDefaults) {
  const ScenarioNetwork n = parse_scenario_network(json::object(), kPath, "/scenarios");
  EXPECT_EQ(n.initial_slice, "eMBB");
  EXPECT_TRUE(n.degradations.empty());
  EXPECT_EQ(n.trace, "");
  EXPECT_DOUBLE_EQ(n.trace_period_s, 20.0);
  EXPECT_DOUBLE_EQ(n.link.handover_delay_ms, LinkEmulatorConfig{}.handover_delay_ms);
}

TEST(ScenarioNetworkParser, ReadsEveryField) {
  const ScenarioNetwork n = parse_scenario_network(json::parse(R"({
    "initial_slice": "URLLC", "degradations": [{"start_s": 30, "duration_s": 12.5}, {"start_s": 0, "duration_s": 1}],
    "trace": "traces/t.json", "trace_period_s": 5,
    "link": {"handover_delay_ms": 250, "reordering": true}})"), kPath, "/scenarios");
  EXPECT_EQ(n.initial_slice, "URLLC");
  ASSERT_EQ(n.degradations.size(), 2u);
  EXPECT_DOUBLE_EQ(n.degradations[0].start_s, 30.0);
  EXPECT_DOUBLE_EQ(n.degradations[0].duration_s, 12.5);
  EXPECT_EQ(n.trace, "/scenarios/traces/t.json") << "relative to the scenario's folder";
  EXPECT_DOUBLE_EQ(n.trace_period_s, 5.0);
  EXPECT_DOUBLE_EQ(n.link.handover_delay_ms, 250.0);
  EXPECT_TRUE(n.link.link.reordering);
  EXPECT_EQ(parse_scenario_network({{"trace", "alphabench:a/b.json"}}, kPath, "/scenarios").trace, "alphabench:a/b.json");
  EXPECT_EQ(parse_scenario_network({{"trace", "/abs/t.json"}}, kPath, "/scenarios").trace, "/abs/t.json");
}

TEST(ScenarioNetworkParser, EachBadFieldIsRefusedNamingItsPath) {
  EXPECT_EQ(error_of(json::array()), kPath + ": expected an object, got array");
  EXPECT_EQ(error_of({{"initial_slice", "LTE"}}), kPath + "/initial_slice: 'LTE' is not URLLC, eMBB or mMTC");
  EXPECT_EQ(error_of({{"initial_slice", 5}}), kPath + "/initial_slice: expected a string, got number");
  EXPECT_EQ(error_of({{"degradations", json::object()}}), kPath + "/degradations: expected an array, got object");
  EXPECT_EQ(error_of({{"degradations", {{{"start_s", 1}}}}}), kPath + "/degradations/0/duration_s: missing");
  EXPECT_EQ(error_of({{"degradations", {{{"start_s", -1}, {"duration_s", 2}}}}}),
            kPath + "/degradations/0: start_s >= 0 and duration_s > 0");
  EXPECT_EQ(error_of({{"degradations", {{{"start_s", 1}, {"duration_s", 0}}}}}),
            kPath + "/degradations/0: start_s >= 0 and duration_s > 0");
  EXPECT_EQ(error_of({{"trace", 3}}), kPath + "/trace: expected a string, got number");
  EXPECT_EQ(error_of({{"trace_period_s", 0}}), kPath + "/trace_period_s: must be > 0");
  EXPECT_EQ(error_of({{"trace_period_s", "5"}}), kPath + "/trace_period_s: expected a number, got string");
  EXPECT_EQ(error_of({{"link", 1}}), kPath + "/link: expected an object, got number");
  EXPECT_EQ(error_of({{"link", {{"slice", "URLLC"}}}}), kPath + "/link/slice: set by network/initial_slice, not here");
  EXPECT_EQ(error_of({{"link", {{"seed", 3}}}}), kPath + "/link/seed: set by the run's --seed, not here");
  EXPECT_EQ(error_of({{"link", {{"trace", json::object()}}}}),
            kPath + "/link/trace: set by network/trace and trace_period_s, not here");
  EXPECT_EQ(error_of({{"link", {{"degradations", json::array()}}}}),
            kPath + "/link/degradations: set by network/degradations, not here");
  EXPECT_NE(error_of({{"link", {{"handover_delay_msec", 1}}}}).find(kPath + "/link/handover_delay_msec: unknown setting"),
            std::string::npos);
  EXPECT_NE(error_of({{"link", {{"handover_delay_ms", -1}}}}).find(kPath + "/link/handover_delay_ms: -1 must be a number >= 0"),
            std::string::npos)
      << error_of({{"link", {{"handover_delay_ms", -1}}}});
}

}  // namespace
}  // namespace a3::linkemu
