// Scenarios end to end: `a3rig run` refuses every kind of bad scenario before anything runs
// (exit 2, the JSON path in the message, no output folder), and the initial state's battery,
// wind and the mission's time limit change the flight as they should (short virtual-time runs).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <unistd.h>

#include "rigs/scenario/scenario.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

using json = nlohmann::json;

json nfz_detour() { return builtin_scenario_json("nfz-detour").value(); }

std::filesystem::path temp_dir() {
  const auto dir = std::filesystem::temp_directory_path() / ("a3rig-test-scenario-run-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

std::filesystem::path write_scenario(const json& doc, const std::string& name) {
  const auto path = temp_dir() / (name + ".json");
  std::ofstream(path) << doc.dump(1);
  return path;
}

struct BadScenario {
  std::string name;
  std::function<void(json&)> edit;
  std::string path;  // expected in the message
};

TEST(ScenarioRun, EveryKindOfBadScenarioExitsTwoNamingThePathAndWritesNothing) {
  const std::vector<BadScenario> cases = {
      {"home-outside", [](json& d) { d["initial_state"]["uav"]["pose"]["x"] = 1e308; }, "/initial_state/uav/pose"},
      {"home-in-nfz", [](json& d) { d["initial_state"]["uav"]["pose"]["x"] = 400; }, "/initial_state/uav/pose"},
      {"goal-in-nfz", [](json& d) { d["mission"]["objectives"][0]["point"] = {400, 120}; }, "/mission/objectives/0/point"},
      {"wind", [](json& d) { d["initial_state"]["env"]["wind_mps"] = 1e6; }, "/initial_state/env/wind_mps"},
      {"time-limit", [](json& d) { d["mission"]["time_limit_s"] = -1; }, "/mission/time_limit_s"},
      {"null-alt-bounds", [](json& d) { d["initial_state"]["policy"]["alt_bounds"] = nullptr; }, "/initial_state/policy/alt_bounds"},
      {"no-weather", [](json& d) { d["initial_state"]["env"].erase("weather"); }, "/initial_state/env"},
      {"bool-time", [](json& d) { d["initial_state"]["time_s"] = true; }, "/initial_state/time_s"},
      {"battery", [](json& d) { d["initial_state"]["uav"]["energy"]["battery_pct"] = -5; }, "/initial_state/uav/energy/battery_pct"},
      {"speed-type", [](json& d) { d["mission"]["cruise_speed_mps"] = "fast"; }, "/mission/cruise_speed_mps"},
      {"speed-negative", [](json& d) { d["mission"]["cruise_speed_mps"] = -3; }, "/mission/cruise_speed_mps"},
      {"heavy", [](json& d) { d["initial_state"]["uav"]["payloads"] = {{{"id", "anvil"}, {"mass_kg", 3.0}}}; }, "/initial_state/uav/payloads"},
      {"link", [](json& d) { d["network"]["link"] = {{"handover_delay_msec", 5}}; }, "/network/link"},
  };
  for (const auto& c : cases) {
    json doc = nfz_detour();
    c.edit(doc);
    const auto file = write_scenario(doc, c.name);
    const auto out = temp_dir() / ("out-" + c.name);
    const auto r = test::run_command(test::a3rig() + " run --runtime virtual --scenario " + test::quote(file.string()) +
                                         " --out " + test::quote(out.string()),
                                     true);
    EXPECT_EQ(r.exit_status, 2) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(file.string() + ": " + c.path), std::string::npos) << c.name << ": " << r.output;
    EXPECT_EQ(r.output.find("json.exception"), std::string::npos) << c.name << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
  }
  std::filesystem::remove_all(temp_dir());
}

struct Flight {
  double initial_battery_pct = 0.0;
  double final_battery_pct = 0.0;
  std::string status;
  double mission_time_s = 0.0;
};

// nfz-detour with the edit, flown for at most 40 s of mission time.
Flight fly(const std::string& tag, const std::function<void(json&)>& edit) {
  json doc = nfz_detour();
  doc["mission"]["time_limit_s"] = 40;
  edit(doc);
  RunOptions o = test::virtual_run(write_scenario(doc, tag).string(), "scenario-" + tag);
  const RunResult r = test::run(o);
  std::filesystem::remove_all(o.out_dir);
  // Cut short by the time limit, the dialogue is too short to score; the initial state must be valid.
  const std::string problems = test::score(r.episode).problems;
  EXPECT_EQ(problems.find("/initial_state"), std::string::npos) << tag << ": " << problems;
  return {r.episode["initial_state"]["uav"]["energy"]["battery_pct"].get<double>(),
          r.episode["final_state"]["uav"]["energy"]["battery_pct"].get<double>(), r.status, r.mission_time_s};
}

TEST(ScenarioRun, BatteryWindAndTimeLimitChangeTheFlight) {
  const Flight full = fly("full", [](json&) {});
  const Flight partial = fly("partial", [](json& d) { d["initial_state"]["uav"]["energy"]["battery_pct"] = 60; });
  const Flight windy = fly("windy", [](json& d) { d["initial_state"]["env"]["wind_mps"] = 9; });
  std::filesystem::remove_all(temp_dir());
  // The time limit ends the flight.
  EXPECT_EQ(full.status, "time_limit");
  EXPECT_NEAR(full.mission_time_s, 40.0, 2.0);
  // 60 % starts at 60 %: the episode says so and the flight ends near 40 points below a full one.
  EXPECT_DOUBLE_EQ(full.initial_battery_pct, 100.0);
  EXPECT_DOUBLE_EQ(partial.initial_battery_pct, 60.0);
  EXPECT_LT(partial.final_battery_pct, 60.0);
  EXPECT_NEAR(full.final_battery_pct - partial.final_battery_pct, 40.0, 2.0);
  // Holding against 9 m/s of wind costs more energy than still air at 3 m/s.
  EXPECT_LT(windy.final_battery_pct, full.final_battery_pct);
}

}  // namespace
}  // namespace a3::rigs
