// The simulated weather_service: request_weather_update answers the scenario's env (weather,
// wind_mps, wind_dir_deg, and gust_mps when given, else wind × gust_factor) with an advisory:
// "no_fly" when the weather is one of no_fly_weather or gusts reach no_fly_gust_mps,
// "caution" when gusts reach caution_gust_mps, else "ok".
#pragma once

#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "agent/vehicle/peer_answer.hpp"

namespace a3::agent {

struct WeatherConfig {
  double gust_factor = 1.4;        // gust = wind × this when env has no gust_mps
  double caution_gust_mps = 10.0;
  double no_fly_gust_mps = 15.0;
  std::set<std::string> no_fly_weather = {"thunderstorm", "storm", "hail", "heavy_snow"};

  void validate(const std::string& where) const;
};

class WeatherService {
 public:
  // env: the scenario's initial_state.env. Throws std::invalid_argument naming the field
  // ("env.wind_mps: expected a number >= 0").
  WeatherService(const nlohmann::json& env, WeatherConfig config);

  PeerAnswer weather_update(const SelfView& self) const;

  const std::string& weather() const { return weather_; }
  double wind_mps() const { return wind_mps_; }
  double wind_dir_deg() const { return wind_dir_deg_; }
  double gust_mps() const { return gust_mps_; }

 private:
  WeatherConfig config_;
  std::string weather_ = "clear";
  double wind_mps_ = 0.0;
  double wind_dir_deg_ = 0.0;
  double gust_mps_ = 0.0;
};

}  // namespace a3::agent
