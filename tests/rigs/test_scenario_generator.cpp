// The mission generator without flying: deterministic documents, every one of 1000 seeds a
// valid scenario whose geometry keeps the promised margins, knobs that do what they say, and
// bad specs refused with the item named.
#include <gtest/gtest.h>

#include "common/json_file.hpp"
#include "rigs/generator/scenario_generator.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "vehicle/safety_gate.hpp"

namespace a3::rigs {
namespace {

nlohmann::json generated(const std::string& spec) { return generate_scenario_json(parse_generator_spec(spec)); }

std::string error_of(const std::string& spec) {
  try {
    (void)generate_scenario(spec);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

std::vector<Eigen::Vector2d> objective_points(const agent::Objective& o) {
  std::vector<Eigen::Vector2d> pts = o.area;
  if (o.type == agent::ObjectiveType::kImagePoint || o.type == agent::ObjectiveType::kDelivery) pts.push_back(o.point);
  return pts;
}

// Home and every objective point inside the geofence and clear of every zone by the gate's margin.
void expect_clear_geometry(const Scenario& s) {
  const double margin = vehicle::GateConfig{}.nfz_margin_m;
  std::vector<Eigen::Vector2d> pts = {s.mission.home_W_m.head<2>()};
  for (const auto& o : s.mission.objectives) {
    for (const auto& p : objective_points(o)) pts.push_back(p);
  }
  for (const auto& p : pts) {
    EXPECT_GE(s.airspace.geofence_clearance_m(p), 50.0) << s.source << " (" << p.transpose() << ")";
    for (const auto& z : s.airspace.no_fly_zones) {
      EXPECT_GE(z.clearance_m(p), margin) << s.source << " zone " << z.id << " (" << p.transpose() << ")";
    }
  }
}

TEST(ScenarioGenerator, TheSameSpecGivesTheSameDocumentByteForByte) {
  for (const char* spec : {"gen:7", "gen:7:hard", "gen:123456789:easy+traffic=1"}) {
    EXPECT_EQ(generated(spec).dump(2), generated(spec).dump(2)) << spec;
  }
  EXPECT_NE(generated("gen:7:hard").dump(), generated("gen:8:hard").dump());
  // The spelled-out spec of a document is the same mission.
  const GeneratorSpec spec = parse_generator_spec("gen:9:hard+wind=3");
  EXPECT_EQ(generated(generator_spec_text(spec)).dump(), generated("gen:9:hard+wind=3").dump());
}

TEST(ScenarioGenerator, AThousandSeedsAllLoadAsValidScenariosWithClearGeometry) {
  int count = 0;
  for (const std::string difficulty : {"easy", "medium", "hard"}) {
    for (int seed = 1; seed <= 334; ++seed) {
      const std::string spec = "gen:" + std::to_string(seed) + ":" + difficulty;
      const Scenario s = load_scenario_spec(spec, ".");  // the schema and the semantic checks of a file
      EXPECT_EQ(s.source, spec);
      expect_clear_geometry(s);
      EXPECT_GE(s.mission.time_limit_s, 300.0) << spec;
      ++count;
    }
  }
  EXPECT_GE(count, 1000);
}

TEST(ScenarioGenerator, CountKnobsSetWhatTheyName) {
  const nlohmann::json d = generated("gen:3:easy+nfz=3+traffic=1+degradations=0+survey=1+objectives=2");
  EXPECT_EQ(d["airspace"]["no_fly_zones"].size(), 3u);
  EXPECT_EQ(d["airspace"]["traffic"].size(), 1u);
  EXPECT_FALSE(d["network"].contains("degradations"));
  EXPECT_EQ(generated("gen:3:easy+degradations=2")["network"]["degradations"].size(), 2u);
  const auto& objectives = d["mission"]["objectives"];
  ASSERT_EQ(objectives.size(), 3u);  // and return_and_land
  int surveys = 0;
  for (const auto& o : objectives) surveys += o["type"] == "survey";
  EXPECT_EQ(surveys, 1);
  EXPECT_EQ(objectives.back()["type"], "return_and_land");
  EXPECT_FALSE(generated("gen:3:easy").contains("airspace"));
}

TEST(ScenarioGenerator, WeatherPayloadAirframeAndSliceKnobs) {
  const nlohmann::json d = generated("gen:4:medium+wind=6+gust=8+slice=mMTC+payload=2+delivery=1");
  EXPECT_EQ(d["initial_state"]["env"]["wind_mps"], 6.0);
  EXPECT_EQ(d["initial_state"]["env"]["gust_mps"], 8.0);
  EXPECT_EQ(d["network"]["initial_slice"], "mMTC");
  EXPECT_EQ(d["airframe"], "heavy-lift");  // 2 kg is beyond the Iris
  ASSERT_EQ(d["initial_state"]["uav"]["payloads"].size(), 1u);
  EXPECT_EQ(d["initial_state"]["uav"]["payloads"][0]["mass_kg"], 2.0);
  EXPECT_EQ(d["initial_state"]["uav"]["payloads"][0]["category"], "delivery");
  EXPECT_EQ(generated("gen:4:easy+payload=0")["airframe"], "iris");
  EXPECT_TRUE(generated("gen:4:easy+payload=0")["initial_state"]["uav"]["payloads"].empty());
}

TEST(ScenarioGenerator, DifficultyRaisesTheChallenge) {
  const nlohmann::json easy = generated("gen:5:easy"), medium = generated("gen:5:medium"), hard = generated("gen:5:hard");
  EXPECT_LT(easy["initial_state"]["env"]["wind_mps"].get<double>(), hard["initial_state"]["env"]["wind_mps"].get<double>());
  EXPECT_EQ(easy["mission"]["objectives"].size(), 2u);
  EXPECT_EQ(medium["mission"]["objectives"].size(), 3u);
  EXPECT_EQ(medium["airspace"]["no_fly_zones"].size(), 1u);
  EXPECT_EQ(hard["airspace"]["no_fly_zones"].size(), 2u);
  EXPECT_EQ(hard["airspace"]["traffic"].size(), 1u);
}

TEST(ScenarioGenerator, ImpossibleKnobsAreRefusedWithTheReason) {
  EXPECT_NE(error_of("gen:1:medium+airframe=iris+payload=3").find("payload"), std::string::npos);
  EXPECT_NE(error_of("gen:1:easy+wind=15+gust=16").find("wind"), std::string::npos);
  EXPECT_NE(error_of("gen:1:easy+objectives=3+turns=8").find("turns=8"), std::string::npos);
  EXPECT_NE(error_of("gen:1:easy+delivery=1+payload=0").find("payload"), std::string::npos);
}

TEST(ScenarioGenerator, BadSpecsNameTheItem) {
  EXPECT_NE(error_of("gen:abc").find("gen:SEED"), std::string::npos);
  EXPECT_NE(error_of("gen:1:bogus=2").find("'bogus'"), std::string::npos);
  EXPECT_NE(error_of("gen:1:wind=-1").find("wind='-1'"), std::string::npos);
  EXPECT_NE(error_of("gen:1:extreme").find("'extreme'"), std::string::npos);
  EXPECT_NE(error_of("gen:1:turns=14").find("turns=14"), std::string::npos);
  EXPECT_NE(error_of("gen:1:easy++wind=2").find("empty knob"), std::string::npos);
}

}  // namespace
}  // namespace a3::rigs

namespace a3::rigs {
namespace {

// gen: specs are resolved before loading: the loader refuses one, saying where it is made.
TEST(ScenarioSpec, TheLoaderNeverGeneratesTheSpecLoaderDoes) {
  try {
    (void)load_scenario("gen:7:hard", ".");
    FAIL() << "the loader generated a mission";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("load_scenario_spec"), std::string::npos) << e.what();
  }
  EXPECT_EQ(load_scenario_spec("gen:7:hard", ".").source, "gen:7:hard");
  EXPECT_EQ(load_scenario_spec("nfz-detour", ".").name, load_scenario("nfz-detour", ".").name);
}

}  // namespace
}  // namespace a3::rigs
