// initial_state.uav.payloads, parsed once (rigs/scenario/uav_payloads.hpp) into the dynamics'
// physical payloads and the sensor suite's declared ones: every field read, defaults, each bad
// field refused naming its JSON path; and parse_initial_state hands both parts, the sensors'
// health and the env on as typed values.
#include <gtest/gtest.h>

#include <string>

#include "common/json_file.hpp"
#include "rigs/scenario/initial_state.hpp"
#include "rigs/scenario/uav_payloads.hpp"
#include "vehicle/sensor_suite.hpp"

namespace a3::rigs {
namespace {

using nlohmann::json;

const std::string kPath = "s.json: /initial_state/uav/payloads";

std::string payload_error(const json& payloads) {
  try {
    (void)parse_uav_payloads(payloads, kPath);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(UavPayloadsParser, ReadsThePhysicalAndTheDeclaredPartOfEachPayload) {
  const json doc = json::parse(R"([
    {"id": "cam", "type": "gimbaled_camera", "category": "imaging_optical", "mass_kg": 3.2,
     "power_W": 45, "drag_cdA": 0.01, "mount": "belly", "constraints": {"max_speed_mps": 12}},
    {"type": "parcel_delivery_system", "mass_kg": 1.8}])");
  const UavPayloads p = parse_uav_payloads(doc, kPath);
  ASSERT_EQ(p.physical.size(), 2u);
  ASSERT_EQ(p.declared.size(), 2u);
  EXPECT_EQ(p.physical[0].id, "cam");
  EXPECT_DOUBLE_EQ(p.physical[0].mass_kg, 3.2);
  EXPECT_DOUBLE_EQ(p.physical[0].drag_cdA_m2, 0.01);
  EXPECT_DOUBLE_EQ(p.physical[0].power_W, 45.0);
  EXPECT_EQ(p.declared[0].id, "cam");
  EXPECT_EQ(p.declared[0].type, "gimbaled_camera");
  EXPECT_EQ(p.declared[0].category, "imaging_optical");
  EXPECT_DOUBLE_EQ(p.declared[0].power_W, 45.0);
  EXPECT_EQ(p.physical[1].id, "payload1") << "a payload without an id is named by its index";
  EXPECT_EQ(p.declared[1].id, "payload1") << "the sensor suite knows it by the same name";
  EXPECT_EQ(p.declared[1].type, "parcel_delivery_system");
  EXPECT_EQ(p.declared[1].category, "");
  EXPECT_DOUBLE_EQ(p.physical[1].drag_cdA_m2, 0.0);
  EXPECT_DOUBLE_EQ(p.physical[1].power_W, 0.0);
  EXPECT_TRUE(parse_uav_payloads(json(), kPath).physical.empty()) << "null: no payloads";
}

TEST(UavPayloadsParser, TheSensorSuiteTakesPayloadsWithoutAnIdAsTheCorpusWritesThem) {
  const json doc = json::parse(R"([{"type": "parcel_delivery_system", "mass_kg": 1.2},
                                   {"type": "thermal_camera", "category": "imaging_thermal", "mass_kg": 0.3}])");
  vehicle::SensorSuiteConfig config;
  config.payloads = parse_uav_payloads(doc, kPath).declared;
  const vehicle::SensorSuite suite(config, vehicle::ImageSizes{});
  ASSERT_NE(suite.find("payload1"), nullptr);
  EXPECT_TRUE(suite.find("payload1")->imaging);
  EXPECT_FALSE(suite.find("payload0")->imaging);
}

TEST(UavPayloadsParser, EachBadFieldIsRefusedNamingItsPath) {
  EXPECT_EQ(payload_error(json::object()), kPath + ": payloads must be an array");
  EXPECT_EQ(payload_error(json::array({json::object(), 7})), kPath + "/1: a payload must be an object");
  for (const char* key : {"mass_kg", "drag_cdA", "power_W"}) {
    EXPECT_EQ(payload_error(json::array({{{key, -2}}})), kPath + "/0/" + key + ": must be >= 0, got -2.000000");
    EXPECT_EQ(payload_error(json::array({{{key, "heavy"}}})), kPath + "/0/" + key + ": expected a number, got string");
  }
  for (const char* key : {"id", "type", "category"}) {
    EXPECT_EQ(payload_error(json::array({{{"mass_kg", 1}}, {{key, 5}}})), kPath + "/1/" + key + ": expected a string, got number");
  }
}

json initial_state() {
  return json::parse(R"({
    "domain": "uav", "time_s": 0,
    "env": {"weather": "dust", "wind_mps": 4, "wind_dir_deg": 90, "gust_mps": 7},
    "airspace": {},
    "uav": {"pose": {"x": 1, "y": 2, "z": 0}, "energy": {"battery_pct": 80},
            "sensors": {"rgb": "ok", "thermal": "degraded"},
            "payloads": [{"id": "ir", "category": "imaging_thermal", "mass_kg": 0.4, "power_W": 9}]},
    "policy": {}})");
}

TEST(InitialStateSections, EnvSensorsAndPayloadsArriveTyped) {
  const InitialState s = parse_initial_state(initial_state(), "s.json: /initial_state");
  EXPECT_EQ(s.env.weather, "dust");
  EXPECT_DOUBLE_EQ(s.env.wind_mps, 4.0);
  EXPECT_DOUBLE_EQ(s.env.gust_mps.value(), 7.0);
  EXPECT_EQ(s.sensors.sensor_health.at("thermal"), "degraded");
  ASSERT_EQ(s.sensors.payloads.size(), 1u);
  EXPECT_EQ(s.sensors.payloads[0].category, "imaging_thermal");
  ASSERT_EQ(s.payloads.size(), 1u);
  EXPECT_DOUBLE_EQ(s.payloads[0].mass_kg, 0.4);
  EXPECT_DOUBLE_EQ(flight_start(s).wind_mps, 4.0);
}

TEST(InitialStateSections, ErrorsInEachSectionNameTheirPathUnderInitialState) {
  const auto error = [](const json& state) {
    try {
      (void)parse_initial_state(state, "s.json: /initial_state");
    } catch (const common::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  json s = initial_state();
  s["env"]["wind_mps"] = -1;
  EXPECT_EQ(error(s), "s.json: /initial_state/env/wind_mps: must be >= 0");
  s = initial_state();
  s["uav"]["sensors"]["rgb"] = false;
  EXPECT_EQ(error(s), "s.json: /initial_state/uav/sensors/rgb: expected a health string (\"ok\", \"offline\", ...)");
  s = initial_state();
  s["uav"]["payloads"][0]["mass_kg"] = -1;
  EXPECT_EQ(error(s), "s.json: /initial_state/uav/payloads/0/mass_kg: must be >= 0, got -1.000000");
  s = initial_state();
  s["uav"]["payloads"] = {{"id", "x"}};
  EXPECT_EQ(error(s), "s.json: /initial_state/uav/payloads: expected an array, got object");
  s = initial_state();
  s["uav"]["payloads"][0]["id"] = "thermal";
  EXPECT_EQ(error(s), "s.json: /initial_state/uav/payloads/0/id: 'thermal' is also the name of a sensor in uav/sensors");
  s = initial_state();
  s["uav"]["payloads"] = json::parse(R"([{"mass_kg": 1}, {"id": "payload0", "mass_kg": 1}])");
  EXPECT_EQ(error(s), "s.json: /initial_state/uav/payloads/1/id: 'payload0' is also the id of an earlier payload");
}

}  // namespace
}  // namespace a3::rigs
