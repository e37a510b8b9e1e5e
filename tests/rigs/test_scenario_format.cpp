// The scenario format (rigs/schema/scenario.schema.json, rigs/scenario/scenario_checks.hpp): every
// kind of bad scenario a user found accepted is refused with its file and JSON path, the
// built-in scenarios and the public corpus' initial states load, and fields are honoured
// (network.link, policy.alt_bounds, battery_pct, gust) rather than dropped.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/json_file.hpp"
#include "common/json_text.hpp"
#include "rigs/scenario/builtin_scenarios.hpp"
#include "rigs/scenario/scenario.hpp"
#include "rigs/scenario/scenario_checks.hpp"
#include "rigs/scenario/scenario_schema.hpp"
#include "tests/test_support.hpp"

namespace a3::rigs {
namespace {

using json = nlohmann::json;

json nfz_detour() { return builtin_scenario_json("nfz-detour").value(); }

// The error of loading `doc`, or "" when it loads.
std::string load_error(const json& doc) {
  try {
    (void)scenario_from_json(doc, "bad.json", ".");
    return "";
  } catch (const common::InputError& e) {
    return e.what();
  }
}

void expect_refused(const json& doc, const std::string& path) {
  const std::string error = load_error(doc);
  EXPECT_NE(error.find("bad.json: " + path), std::string::npos) << "expected " << path << ", got: " << error;
}

TEST(ScenarioFormat, EveryBuiltInScenarioPassesTheSchemaAndTheRules) {
  for (const auto& [name, text] : builtin_scenarios()) {
    const json doc = common::parse_json_text(text, std::string(name));
    EXPECT_TRUE(scenario_schema_problems(doc, std::string(name)).empty()) << name;
    EXPECT_EQ(load_error(doc), "") << name;
  }
}

TEST(ScenarioFormat, EveryTestDataScenarioPassesTheSchemaAndTheRules) {
  const std::filesystem::path dir = std::filesystem::path(A3_SOURCE_DIR) / "tests" / "data" / "scenarios";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << dir << " is absent";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW((void)load_scenario(entry.path().string(), ".")) << entry.path();
  }
}

TEST(ScenarioFormat, HomeOutsideTheGeofenceIsRefused) {
  json doc = nfz_detour();
  doc["initial_state"]["uav"]["pose"]["x"] = -50.0;
  expect_refused(doc, "/initial_state/uav/pose");
  doc["initial_state"]["uav"]["pose"]["x"] = 1e308;
  expect_refused(doc, "/initial_state/uav/pose");
}

TEST(ScenarioFormat, HomeInsideANoFlyZoneIsRefused) {
  json doc = nfz_detour();
  doc["initial_state"]["uav"]["pose"]["x"] = 400.0;  // the hospital's centre
  const std::string error = load_error(doc);
  EXPECT_NE(error.find("bad.json: /initial_state/uav/pose"), std::string::npos) << error;
  EXPECT_NE(error.find("hospital"), std::string::npos) << error;
}

TEST(ScenarioFormat, AGoalInsideANoFlyZoneIsRefusedAtItsAltitude) {
  json doc = nfz_detour();
  doc["mission"]["objectives"][0]["point"] = {420, 100};
  expect_refused(doc, "/mission/objectives/0/point");
  // A zone whose ceiling is below the objective's altitude does not contain it.
  doc["airspace"]["no_fly_zones"][0]["ceiling_m"] = 40;
  EXPECT_EQ(load_error(doc), "");
}

TEST(ScenarioFormat, AnAreaOverlappingANoFlyZoneIsRefused) {
  json doc = nfz_detour();
  doc["mission"]["objectives"][0] = {{"id", "field"}, {"type", "survey"}, {"area", {{300, 50}, {380, 50}, {380, 150}, {300, 150}}},
                                     {"altitude_m", 60}};
  expect_refused(doc, "/mission/objectives/0/area");
}

TEST(ScenarioFormat, WindTheAirframeCannotHoldAgainstIsRefused) {
  for (const double wind : {1e6, 1e308, 15.0}) {
    json doc = nfz_detour();
    doc["initial_state"]["env"]["wind_mps"] = wind;
    expect_refused(doc, "/initial_state/env/wind_mps");
  }
  json doc = nfz_detour();
  doc["initial_state"]["env"]["gust_mps"] = 30.0;
  expect_refused(doc, "/initial_state/env/gust_mps");
  // The Iris holds about 13 m/s at its 30° tilt limit; 80 % of that is allowed as mean wind.
  const double limit = wind_hold_limit_mps(dynamics::airframe_by_name_or_path("iris"), 30.0);
  EXPECT_GT(limit, 11.0);
  EXPECT_LT(limit, 15.0);
  doc["initial_state"]["env"]["gust_mps"] = limit - 0.5;
  doc["initial_state"]["env"]["wind_mps"] = kWindMargin * limit - 0.5;
  EXPECT_EQ(load_error(doc), "");
}

TEST(ScenarioFormat, APayloadBeyondTheAirframesLiftIsRefused) {
  json doc = nfz_detour();
  doc["initial_state"]["uav"]["payloads"] = {{{"id", "anvil"}, {"mass_kg", 3.0}}};
  expect_refused(doc, "/initial_state/uav/payloads");
}

TEST(ScenarioFormat, ANonPositiveTimeLimitOrCruiseSpeedIsRefusedNamingTheMissionField) {
  for (const double t : {0.0, -1.0}) {
    json doc = nfz_detour();
    doc["mission"]["time_limit_s"] = t;
    expect_refused(doc, "/mission/time_limit_s");
  }
  json doc = nfz_detour();
  doc["mission"]["cruise_speed_mps"] = -3.0;
  expect_refused(doc, "/mission/cruise_speed_mps");
  EXPECT_EQ(load_error(doc).find("ToolServerConfig"), std::string::npos);
}

TEST(ScenarioFormat, ShapesThatWouldWriteAnInvalidEpisodeAreRefused) {
  json doc = nfz_detour();
  doc["initial_state"]["policy"]["alt_bounds"] = nullptr;
  expect_refused(doc, "/initial_state/policy/alt_bounds");
  doc = nfz_detour();
  doc["initial_state"]["env"].erase("weather");
  expect_refused(doc, "/initial_state/env");
  EXPECT_NE(load_error(doc).find("weather"), std::string::npos);
  doc = nfz_detour();
  doc["initial_state"]["time_s"] = true;
  expect_refused(doc, "/initial_state/time_s");
}

TEST(ScenarioFormat, ABatteryOutsideZeroToAHundredIsRefusedAndSixtyIsKept) {
  for (const double pct : {-5.0, 0.0, 100.5}) {
    json doc = nfz_detour();
    doc["initial_state"]["uav"]["energy"]["battery_pct"] = pct;
    expect_refused(doc, "/initial_state/uav/energy/battery_pct");
  }
  json doc = nfz_detour();
  doc["initial_state"]["uav"]["energy"]["battery_pct"] = 60.0;
  EXPECT_DOUBLE_EQ(scenario_from_json(doc, "ok.json", ".").start.battery_pct, 60.0);
}

TEST(ScenarioFormat, TypeErrorsAndUnknownFieldsNameTheirPathNotTheLibrary) {
  json doc = nfz_detour();
  doc["mission"]["cruise_speed_mps"] = "fast";
  expect_refused(doc, "/mission/cruise_speed_mps");
  EXPECT_EQ(load_error(doc).find("json.exception"), std::string::npos);
  doc = nfz_detour();
  doc["mission"]["objectives"][0]["area"] = {{0, 0}, {1, 0}, {1, 1}};  // not a field of image_point
  expect_refused(doc, "/mission/objectives/0");
  doc = nfz_detour();
  doc["mission"]["cruise_altitude"] = 60;  // a typo
  expect_refused(doc, "/mission");
  doc = nfz_detour();
  doc["initial_state"]["airspace"]["geofence"].push_back(doc["initial_state"]["airspace"]["geofence"][0]);
  expect_refused(doc, "/initial_state/airspace/geofence");
}

TEST(ScenarioFormat, EveryProblemIsReportedOnItsOwnLine) {
  json doc = nfz_detour();
  doc["mission"]["time_limit_s"] = 0;
  doc["initial_state"]["uav"]["energy"]["battery_pct"] = -5;
  const std::string error = load_error(doc);
  EXPECT_NE(error.find("bad.json: /mission/time_limit_s"), std::string::npos) << error;
  EXPECT_NE(error.find("\nbad.json: "), std::string::npos) << error;
}

TEST(ScenarioFormat, CruiseAltitudeOutsideThePolicyEnvelopeIsRefused) {
  json doc = nfz_detour();
  doc["initial_state"]["policy"]["alt_bounds"] = {0, 50};  // narrower than the airspace's
  expect_refused(doc, "/mission/cruise_altitude_m");
}

TEST(ScenarioFormat, NetworkLinkSettingsAreHonouredOrRefused) {
  json doc = nfz_detour();
  doc["network"]["link"] = {{"handover_delay_ms", 250.0}, {"reordering", true}};
  const Scenario s = scenario_from_json(doc, "ok.json", ".");
  EXPECT_DOUBLE_EQ(s.network.link.handover_delay_ms, 250.0);
  EXPECT_TRUE(s.network.link.link.reordering);
  doc["network"]["link"] = {{"handover_delay_msec", 250.0}};
  expect_refused(doc, "/network/link");
  doc["network"]["link"] = {{"slice", "URLLC"}};
  expect_refused(doc, "/network/link/slice");
  doc["network"]["link"] = {{"handover_delay_ms", -1.0}};
  expect_refused(doc, "/network/link");
}

TEST(ScenarioFormat, TrafficOutOfTimeOrderIsRefused) {
  json doc = nfz_detour();
  doc["airspace"]["traffic"] = {{{"id", "peer"}, {"path", {{{"t_s", 10}, {"p", {0, 0, 50}}}, {{"t_s", 5}, {"p", {10, 0, 50}}}}}}};
  expect_refused(doc, "/airspace/traffic/0/path/1/t_s");
}

// The public states go through the episode schema's `state` and then the same parser and rules;
// the only ones refused carry more payload than any built-in airframe lifts (refused at run
// time before the schema existed, too) or start outside their own geofence.
TEST(ScenarioFormat, EveryPublicInitialStateLoadsOrIsRefusedForAPhysicalReason) {
  const std::filesystem::path runs = test::shared_dir() / "alphabench" / "eval_runs";
  if (!std::filesystem::exists(runs)) GTEST_SKIP() << runs << " is absent (the α³-Bench public episodes)";
  int loaded = 0, refused = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(runs)) {
    if (entry.path().extension() != ".json") continue;
    const std::string spec = "alphabench:" + std::filesystem::relative(entry.path(), runs).string();
    try {
      const Scenario s = load_scenario(spec, test::shared_dir());
      EXPECT_TRUE(s.airspace.inside_geofence(s.mission.objectives[0].point)) << spec;
      ++loaded;
    } catch (const common::InputError& e) {
      const std::string error = e.what();
      const bool physical = error.find(": /initial_state/uav/payloads: ") != std::string::npos ||
                            error.find(": /initial_state/uav/pose: home") != std::string::npos;
      EXPECT_TRUE(physical) << spec << ": " << error;
      ++refused;
    }
  }
  EXPECT_GE(loaded, 8 * refused);  // 180 of the 200 load
}

}  // namespace
}  // namespace a3::rigs
