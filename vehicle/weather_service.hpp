// The simulated weather_service: request_weather_update answers the scenario's env (weather,
// wind_mps, wind_dir_deg, and gust_mps when given, else wind × gust_factor; typed and parsed
// in weather_config.hpp) with an advisory:
// "no_fly" when the weather is one of no_fly_weather or gusts reach no_fly_gust_mps,
// "caution" when gusts reach caution_gust_mps, else "ok".
#pragma once

#include <string>

#include "vehicle/peer_answer.hpp"
#include "vehicle/weather_config.hpp"

namespace a3::vehicle {

class WeatherService {
 public:
  // env: the scenario's initial_state.env. Throws std::invalid_argument naming the field
  // ("env.wind_mps: expected a finite number >= 0", "weather.gust_factor must be >= 1, ...").
  WeatherService(const WeatherEnv& env, WeatherConfig config);

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

}  // namespace a3::vehicle
