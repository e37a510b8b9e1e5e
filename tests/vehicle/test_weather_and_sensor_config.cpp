// The tool server's scenario sections, parsed once into typed configs: initial_state.env into
// WeatherEnv (parse_weather_env) and uav.sensors into sensor health (parse_sensor_health); every
// bad field is refused naming its JSON path, and the typed env is checked again where the
// weather service takes it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "common/json_file.hpp"
#include "vehicle/sensor_suite_config.hpp"
#include "vehicle/weather_config.hpp"
#include "vehicle/weather_service.hpp"

namespace a3::vehicle {
namespace {

using nlohmann::json;

const char* kEnvPath = "s.json: /initial_state/env";

json good_env() { return {{"weather", "rain"}, {"wind_mps", 6.5}, {"wind_dir_deg", 270.0}}; }

std::string env_error(const json& env) {
  try {
    (void)parse_weather_env(env, kEnvPath);
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(WeatherEnvParser, ReadsEveryFieldAndLeavesAnAbsentGustToTheService) {
  const WeatherEnv e = parse_weather_env(good_env(), kEnvPath);
  EXPECT_EQ(e.weather, "rain");
  EXPECT_DOUBLE_EQ(e.wind_mps, 6.5);
  EXPECT_DOUBLE_EQ(e.wind_dir_deg, 270.0);
  EXPECT_FALSE(e.gust_mps.has_value());
  json gusty = good_env();
  gusty["gust_mps"] = 11.0;
  EXPECT_DOUBLE_EQ(parse_weather_env(gusty, kEnvPath).gust_mps.value(), 11.0);
  EXPECT_DOUBLE_EQ(WeatherService(parse_weather_env(gusty, kEnvPath), WeatherConfig{}).gust_mps(), 11.0);
  EXPECT_DOUBLE_EQ(WeatherService(e, WeatherConfig{}).gust_mps(), 6.5 * 1.4) << "wind × gust factor";
}

TEST(WeatherEnvParser, EachBadFieldIsRefusedNamingItsPath) {
  EXPECT_EQ(env_error(json::array()), std::string(kEnvPath) + ": expected an object, got array");
  for (const char* key : {"weather", "wind_mps", "wind_dir_deg"}) {
    json e = good_env();
    e.erase(key);
    EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/" + key + ": missing");
  }
  json e = good_env();
  e["weather"] = 3;
  EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/weather: expected a string, got number");
  e = good_env();
  e["wind_mps"] = "strong";
  EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/wind_mps: expected a number, got string");
  e = good_env();
  e["wind_mps"] = -1.0;
  EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/wind_mps: must be >= 0");
  e = good_env();
  e["wind_dir_deg"] = true;
  EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/wind_dir_deg: expected a number, got boolean");
  e = good_env();
  e["gust_mps"] = -0.5;
  EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/gust_mps: must be >= 0");
  e["gust_mps"] = nullptr;
  EXPECT_EQ(env_error(e), std::string(kEnvPath) + "/gust_mps: expected a number, got null");
}

TEST(WeatherEnvParser, TheServiceRefusesATypedEnvOutOfRangeNamingTheField) {
  const auto error = [](const WeatherEnv& env) {
    try {
      WeatherService service(env, WeatherConfig{});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(error({"clear", -2.0, 0.0, std::nullopt}), "env.wind_mps: expected a finite number >= 0");
  EXPECT_EQ(error({"clear", 2.0, std::nan(""), std::nullopt}), "env.wind_dir_deg: expected a finite number");
  EXPECT_EQ(error({"clear", 2.0, 0.0, -1.0}), "env.gust_mps: expected a finite number >= 0");
  EXPECT_EQ(error({"clear", 2.0, 0.0, 3.0}), "(accepted)");
}

TEST(SensorHealthParser, ReadsHealthByNameAndRefusesANonStringNamingIt) {
  const auto health = parse_sensor_health(json{{"rgb", "ok"}, {"lidar", "offline"}}, "s.json: /uav/sensors");
  ASSERT_EQ(health.size(), 2u);
  EXPECT_EQ(health.at("lidar"), "offline");
  EXPECT_TRUE(parse_sensor_health(json::object(), "s.json: /uav/sensors").empty());
  try {
    (void)parse_sensor_health(json{{"rgb", "ok"}, {"thermal", 1}}, "s.json: /uav/sensors");
    ADD_FAILURE() << "a numeric health was accepted";
  } catch (const common::InputError& e) {
    EXPECT_STREQ(e.what(), "s.json: /uav/sensors/thermal: expected a health string (\"ok\", \"offline\", ...)");
  }
  try {
    (void)parse_sensor_health(json::array(), "s.json: /uav/sensors");
    ADD_FAILURE() << "an array was accepted";
  } catch (const common::InputError& e) {
    EXPECT_STREQ(e.what(), "s.json: /uav/sensors: expected an object, got array");
  }
}

}  // namespace
}  // namespace a3::vehicle
