// The trajectory plot shows the world: the generated gnuplot script has one object per
// no-fly zone (labelled with id, floor and ceiling), the geofence in view, one data block per
// peer with a row per waypoint, one row per safety event grouped by kind with a legend entry;
// and gnuplot, when installed, draws it into a PNG.
#include "rigs/report/trajectory_plot.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "rigs/outputs/episode_writer.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::rigs {
namespace {

a3lcm::safety_event_t event(const std::string& kind, double x_m, double y_m) {
  a3lcm::safety_event_t e{};
  e.kind = kind;
  e.source = "test";
  e.p_W_m[0] = x_m;
  e.p_W_m[1] = y_m;
  e.p_W_m[2] = 60.0;
  return e;
}

agent::TrafficWaypoint waypoint(double t_s, double x_m, double y_m) { return {t_s, Eigen::Vector3d(x_m, y_m, 60.0)}; }

// Home at (100, 100); a 3 km geofence much larger than the flown track; a polygon and a
// cylinder zone; two peers; five events of three kinds.
Scenario world() {
  Scenario s;
  s.name = "plot-world";
  s.mission.home_W_m = {100.0, 100.0, 0.0};
  agent::Objective tower;
  tower.id = "tower";
  tower.type = agent::ObjectiveType::kImagePoint;
  tower.point = {300.0, 200.0};
  s.mission.objectives.push_back(tower);
  s.airspace.geofence = {{-1000, -1000}, {2000, -1000}, {2000, 2000}, {-1000, 2000}};
  agent::NoFlyZone hospital;
  hospital.id = "hospital";
  hospital.centre = {200.0, 100.0};
  hospital.radius_m = 40.0;
  hospital.floor_m = 0.0;
  hospital.ceiling_m = 500.0;
  agent::NoFlyZone prison;
  prison.id = "prison";
  prison.polygon = {{250, 250}, {320, 250}, {320, 320}, {250, 320}};
  prison.ceiling_m = 120.0;
  s.airspace.no_fly_zones = {hospital, prison};
  agent::TrafficPlan patrol;
  patrol.id = "patrol-7";
  patrol.path = {waypoint(0, 400, 300), waypoint(20, 400, 300), waypoint(120, 150, 300), waypoint(220, 400, 300)};
  agent::TrafficPlan survey;
  survey.id = "survey-2";
  survey.path = {waypoint(0, 50, 400), waypoint(90, 350, 400)};
  s.airspace.traffic = {patrol, survey};
  return s;
}

RecordedEpisode flight() {
  RecordedEpisode rec;
  for (int i = 0; i <= 20; ++i) rec.trajectory.push_back({double(i), 100.0 + 10.0 * i, 100.0 + 5.0 * i, 3.0 * i, 100.0 - 0.5 * i, 8.0});
  rec.safety = {event("nfz_intrusion", 190, 105), event("nfz_intrusion", 195, 104), event("separation_breach", 260, 300),
                event("gate_refusal", 120, 110), event("nfz_intrusion", 210, 110)};
  return rec;
}

int count(const std::string& text, const std::regex& pattern) {
  return static_cast<int>(std::distance(std::sregex_iterator(text.begin(), text.end(), pattern), std::sregex_iterator()));
}

// The rows of the data block NAME ("$peer_0 << EOD" ... "EOD").
std::vector<std::string> block_rows(const std::string& script, const std::string& name) {
  std::vector<std::string> rows;
  std::istringstream in(script.substr(script.find(name + " << EOD\n") + name.size() + 8));
  for (std::string line; std::getline(in, line) && line != "EOD";) rows.push_back(line);
  return rows;
}

const std::string kScript = trajectory_plot_script("/tmp/plot", world(), flight());

TEST(TrajectoryPlotScript, DrawsEveryZoneFilledAndLabelledWithFloorAndCeiling) {
  EXPECT_EQ(count(kScript, std::regex("set object \\d+ circle at 200,100 size 40 fs transparent solid")), 1);
  EXPECT_EQ(count(kScript, std::regex("set object \\d+ polygon from 250,250 to 320,250 to 320,320 to 250,320 to 250,250 fs transparent solid")), 1);
  EXPECT_NE(kScript.find("'hospital 0 m to 500 m' at 200,100"), std::string::npos) << kScript;
  EXPECT_NE(kScript.find("'prison ground to 120 m' at 285,285"), std::string::npos);
  EXPECT_EQ(count(kScript, std::regex("title 'no-fly zone'")), 1);
}

TEST(TrajectoryPlotScript, TheGeofenceIsDrawnAndInView) {
  EXPECT_EQ(count(kScript, std::regex("polygon from -1000,-1000 to 2000,-1000 to 2000,2000 to -1000,2000 to -1000,-1000 fs empty")), 1);
  std::smatch range;
  ASSERT_TRUE(std::regex_search(kScript, range, std::regex("set xrange \\[([-0-9.e]+):([-0-9.e]+)\\]")));
  EXPECT_LT(std::stod(range[1]), -1000.0);
  EXPECT_GT(std::stod(range[2]), 2000.0);
}

TEST(TrajectoryPlotScript, OneBlockPerPeerWithARowPerWaypointAndItsTimes) {
  EXPECT_EQ(count(kScript, std::regex("\\$peer_\\d+ << EOD")), 2);
  const auto patrol = block_rows(kScript, "$peer_0");
  ASSERT_EQ(patrol.size(), 4u);
  EXPECT_EQ(patrol[0], "400 300 \"t=0, 20, 220 s at 60 m\"");
  EXPECT_EQ(patrol[1], "400 300 \"\"");  // the same place: labelled once
  EXPECT_EQ(patrol[2], "150 300 \"t=120 s at 60 m\"");
  EXPECT_EQ(block_rows(kScript, "$peer_1").size(), 2u);
  EXPECT_NE(kScript.find("title 'peer patrol-7 (plan)'"), std::string::npos);
  EXPECT_NE(kScript.find("title 'peer survey-2 (plan)'"), std::string::npos);
}

TEST(TrajectoryPlotScript, OneRowPerEventGroupedByKindWithALegendEntry) {
  const auto nfz = block_rows(kScript, "$events_nfz_intrusion");
  ASSERT_EQ(nfz.size(), 3u);
  EXPECT_EQ(nfz[0], "190 105");
  EXPECT_EQ(block_rows(kScript, "$events_separation_breach"), std::vector<std::string>{"260 300"});
  EXPECT_EQ(block_rows(kScript, "$events_gate_refusal"), std::vector<std::string>{"120 110"});
  EXPECT_NE(kScript.find("title 'nfz_intrusion (3)'"), std::string::npos);
  EXPECT_NE(kScript.find("title 'separation_breach (1)'"), std::string::npos);
  EXPECT_NE(kScript.find("title 'gate_refusal (1)'"), std::string::npos);
}

TEST(TrajectoryPlotScript, ObjectivesAndHomeAreLabelled) {
  EXPECT_NE(kScript.find("'tower' at 300,200 point"), std::string::npos);
  EXPECT_NE(kScript.find("'home' at 100,100 point"), std::string::npos);
}

TEST(TrajectoryPlotScript, QuotesInIdsCannotBreakTheScript) {
  Scenario s = world();
  s.airspace.no_fly_zones[0].id = "St 'Mary'";
  const std::string script = trajectory_plot_script("/tmp/plot", s, flight());
  EXPECT_NE(script.find(R"('St '."'".'Mary'."'".' 0 m to 500 m')"), std::string::npos);
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  a3::test::TempDir dir("trajectory-plot-quotes");
  EXPECT_EQ(write_trajectory_plot(dir.path(), s, flight()), "") << "gnuplot reads the quoted id";
}

TEST(TrajectoryPlotPng, GnuplotDrawsTheWorld) {
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot is not installed";
  a3::test::TempDir dir("trajectory-plot");
  const std::string why = write_trajectory_plot(dir.path(), world(), flight());
  ASSERT_EQ(why, "");
  std::ifstream png(dir.path() / "trajectory.png", std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  std::ifstream log(dir.path() / "gnuplot.log");  // written only when gnuplot had something to say
  std::stringstream warnings;
  warnings << log.rdbuf();
  EXPECT_FALSE(log.is_open()) << "gnuplot warned: " << warnings.str();
}

}  // namespace
}  // namespace a3::rigs
