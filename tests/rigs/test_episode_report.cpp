// The episode report page's assembly (episode_report.hpp); tests/report renders it in Chromium.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "common/json_file.hpp"
#include "rigs/report/episode_report.hpp"
#include "rigs/report/report_world.hpp"
#include "tests/rigs/rig_test_support.hpp"

namespace {

using a3::rigs::episode_report_html;
using nlohmann::json;

json episode_with_text(const std::string& text) {
  json e = a3::test::make_episode();
  e["dialogue"][0]["text"] = text;
  return e;
}

// The JSON between <script type="application/json" id="a3-data"> and its </script>.
std::string data_of(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"a3-data\">";
  const auto from = page.find(open) + open.size();
  return page.substr(from, page.find("</script>", from) - from);
}

bool have_d3() { return std::filesystem::is_regular_file(a3::rigs::d3_script_path()); }

TEST(EpisodeReport, TheEpisodeTextCannotEndTheScriptNorFillPlaceholders) {
  if (!have_d3()) GTEST_SKIP() << a3::rigs::d3_script_path() << " missing (Debian: apt-get install libjs-d3)";
  const std::string tricky = "</script><script>alert(1)</script> @A3_D3@ @A3_JS@";
  const std::string page = episode_report_html(episode_with_text(tricky), std::nullopt, "t");
  const json data = json::parse(data_of(page));  // the whole data block parses: nothing ended it early
  EXPECT_EQ(data["episode"]["dialogue"][0]["text"], tricky);
  EXPECT_EQ(page.find("alert(1)</script>"), std::string::npos);
  EXPECT_EQ(page.find("@A3_"), page.find("@A3_D3@ @A3_JS@"));  // only inside the (escaped) episode
}

TEST(EpisodeReport, CarriesTheScoreAndTheWorld) {
  if (!have_d3()) GTEST_SKIP() << a3::rigs::d3_script_path() << " missing (Debian: apt-get install libjs-d3)";
  const auto scenario = a3::rigs::load_scenario("nfz-detour", a3::test::shared_dir());
  const json data = json::parse(data_of(episode_report_html(a3::test::make_episode(), scenario, "t")));
  EXPECT_TRUE(data["score"]["valid"].get<bool>());
  EXPECT_GT(data["score"]["alpha3"].get<double>(), 0.0);
  ASSERT_EQ(data["world"]["zones"].size(), scenario.airspace.no_fly_zones.size());
  EXPECT_EQ(data["world"]["zones"][0]["id"], scenario.airspace.no_fly_zones[0].id);
  EXPECT_EQ(data["world"]["objectives"].size(), scenario.mission.objectives.size());
}

TEST(EpisodeReport, ACylinderWithoutFloorOrCeilingIsNullNotInfinity) {
  auto scenario = a3::rigs::load_scenario("nfz-detour", a3::test::shared_dir());
  scenario.airspace.no_fly_zones[0].polygon.clear();
  scenario.airspace.no_fly_zones[0].floor_m = -std::numeric_limits<double>::infinity();
  scenario.airspace.no_fly_zones[0].ceiling_m = std::numeric_limits<double>::infinity();
  const json zone = a3::rigs::report_world_json(scenario)["zones"][0];
  EXPECT_TRUE(zone["floor_m"].is_null());
  EXPECT_TRUE(zone["ceiling_m"].is_null());
  EXPECT_TRUE(zone["polygon"].empty());
}

TEST(EpisodeReport, WithoutD3TheErrorNamesTheFileAndThePackage) {
  setenv("A3_D3_JS", "/nonexistent/d3.min.js", 1);
  try {
    episode_report_html(a3::test::make_episode(), std::nullopt, "t");
    ADD_FAILURE() << "no error";
  } catch (const a3::common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/d3.min.js"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("libjs-d3"), std::string::npos) << e.what();
  }
  unsetenv("A3_D3_JS");
}

TEST(EpisodeReport, TheScenarioOfARigEpisodeIsFoundByName) {
  json e = a3::test::make_episode();
  e["_rig"] = {{"scenario", "nfz-detour"}, {"scenario_source", "scenario nfz-detour"}};
  const auto s = a3::rigs::scenario_of_episode(a3::episode::Episode(a3::episode::Document(e), "e.json"),
                                               a3::test::shared_dir());
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->name, "nfz-detour");
}

}  // namespace
