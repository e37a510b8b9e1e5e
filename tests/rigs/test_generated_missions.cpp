// Generated missions flown by the scripted agent in virtual time, one test per difficulty (with
// the generator's adversity: degradation windows in the mission phases, traffic, wind, payload):
// every episode is a valid α³-Bench episode that the corpus scorer (`a3rig score`) scores as
// re-validation does, the vehicle never enters a no-fly zone (safety events and the 1 Hz
// trajectory) nor comes within the fc's 2 m brake margin of one, never breaches a peer's separation and never crashes, the agent makes no fault of
// its own (a refused command repeated, a timeout never retried), and at least 95 % of the missions succeed (complete, with every
// objective done). Seeds 1..N per difficulty, N = 100 (300 episodes, about 3 CPU-minutes), or
// $A3_GENERATED_MISSIONS; scripts/generated-missions.sh flies thousands.
#include <gtest/gtest.h>

#include <cstdlib>
#include <numeric>

#include "eval/corpus_scorer.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/scenario/scenario.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace a3::rigs {
namespace {

int missions_per_difficulty() {
  const char* text = std::getenv("A3_GENERATED_MISSIONS");
  return text != nullptr && std::atoi(text) > 0 ? std::atoi(text) : 100;
}

// The 1 Hz trajectory samples (t, x, y, z, ...) inside a zone, as "t=..s in zone".
std::string zone_entries(const nlohmann::json& episode, const Scenario& s) {
  std::string out;
  for (const auto& row : episode["_rig"]["trajectory"]["samples_1hz"]) {
    const Eigen::Vector3d p(row[1].get<double>(), row[2].get<double>(), row[3].get<double>());
    if (const agent::NoFlyZone* z = s.airspace.zone_containing(p)) {
      out += "t=" + std::to_string(row[0].get<double>()) + " s in " + z->id + "; ";
    }
  }
  return out;
}

void expect_safe(const nlohmann::json& e, const Scenario& s, const std::string& spec) {
  for (const auto& event : e["_rig"]["safety_events"]) {
    const std::string kind = event.value("kind", "");
    EXPECT_TRUE(kind != "nfz_intrusion" && kind != "crash" && kind != "geofence_exit" && kind != "separation_breach")
        << spec << ": " << event.dump();
  }
  // Whatever the link did, the reference agent made no fault of its own (rigs/outputs/agent_faults.hpp).
  EXPECT_EQ(e["_rig"]["agent_faults"], nlohmann::json::array()) << spec;
  EXPECT_EQ(zone_entries(e, s), "") << spec;
  // Nor near one: the routes' clearance covers the tracking error in the mission's wind, so the
  // flight controller's keep-out brake (2 m outside a zone) never has to act.
  for (const auto& zone : e["_rig"]["no_fly_zone_clearance"]) {
    EXPECT_GT(zone["closest_m"].get<double>(), 2.0) << spec << ": " << zone.dump();
  }
  EXPECT_FALSE(e["_rig"]["trajectory"]["crashed"].get<bool>()) << spec;
  EXPECT_FALSE(e["final_state"]["safety_flags"]["nfz_violation"].get<bool>()) << spec;
}

// The closest any flight came to a no-fly zone, and in which mission.
struct ClosestZone {
  double clearance_m = 1e9;
  std::string where;
  void add(const nlohmann::json& e, const std::string& spec) {
    for (const auto& zone : e["_rig"]["no_fly_zone_clearance"]) {
      if (zone["closest_m"].get<double>() < clearance_m) {
        clearance_m = zone["closest_m"].get<double>();
        where = spec + " " + zone["zone"].get<std::string>();
      }
    }
  }
  std::string text() const {
    if (where.empty()) return "no flight beside a no-fly zone";
    char out[64];
    std::snprintf(out, sizeof out, "closest to a no-fly zone %.2f m", clearance_m);
    return out + (" (" + where + ")");
  }
};

class GeneratedMissions : public ::testing::TestWithParam<std::string> {};

TEST_P(GeneratedMissions, ScriptedAgentFliesThemSafelyAndMostlySucceeds) {
  const int n = missions_per_difficulty();
  const auto out_dir = a3::test::virtual_run("x", "generated-" + GetParam()).out_dir;
  const auto corpus = out_dir / "runs" / "a3rig" / "scripted" / "uav";
  std::filesystem::create_directories(corpus);
  std::vector<double> alpha3;
  std::string failed;
  ClosestZone closest;
  for (int seed = 1; seed <= n; ++seed) {
    const std::string spec = "gen:" + std::to_string(seed) + ":" + GetParam();
    RunOptions o = a3::test::virtual_run(spec, GetParam() + "-" + std::to_string(seed));
    const Scenario s = load_scenario_spec(spec, o.shared_dir);
    const RunResult r = rigs::run_episode(s, o, {}, nullptr);
    const a3::test::Scored scored = a3::test::score(r.episode);
    ASSERT_TRUE(scored.valid) << spec << ": " << scored.problems;
    expect_safe(r.episode, s, spec);
    closest.add(r.episode, spec);
    alpha3.push_back(scored.pillars.alpha3);
    // A mission the agent did not finish (say, the dialogue ended with the vehicle airborne)
    // counts against the success rate; safety and validity hold for every one.
    if (r.status != "completed" || !r.episode.value("success", false)) {
      failed += spec + " (" + r.status + ") " + r.episode["_rig"]["objectives"].dump() + "\n";
    }
    char name[32];
    std::snprintf(name, sizeof name, "sc-%04d-ep-00.json", seed);
    std::filesystem::copy_file(r.episode_path, corpus / name, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::remove_all(o.out_dir);
  }
  // The corpus scorer reads every episode as valid and averages the same α³.
  const eval::JsonSchemaValidator validator(eval::episode_schema_json(), eval::kEpisodeSchemaName);
  const eval::ScoreResult corpus_scores = eval::score_corpus({out_dir / "runs"}, validator, eval::ScoreOptions{});
  ASSERT_EQ(corpus_scores.models.size(), 1u);
  EXPECT_EQ(corpus_scores.valid, static_cast<std::size_t>(n));
  EXPECT_NEAR(corpus_scores.models[0].mean, std::accumulate(alpha3.begin(), alpha3.end(), 0.0) / n, 1e-12);
  const int failures = static_cast<int>(std::count(failed.begin(), failed.end(), '\n'));
  const double success_rate = 1.0 - static_cast<double>(failures) / n;
  std::printf("%s: %d of %d generated missions succeeded (%.1f %%); %s\n%s", GetParam().c_str(), n - failures, n,
              100.0 * success_rate, closest.text().c_str(), failed.c_str());
  EXPECT_GE(success_rate, 0.95) << "missions that failed:\n" << failed;
  std::filesystem::remove_all(out_dir);
}

INSTANTIATE_TEST_SUITE_P(Difficulty, GeneratedMissions, ::testing::Values("easy", "medium", "hard"),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace a3::rigs
