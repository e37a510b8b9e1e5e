// The simulated weather service.
#include "vehicle/weather_service.hpp"

#include <utility>

#include "vehicle/observation_json.hpp"

namespace a3::vehicle {

WeatherService::WeatherService(const WeatherEnv& env, WeatherConfig config) : config_(std::move(config)) {
  config_.validate("weather");
  env.validate("env");
  weather_ = env.weather;
  wind_mps_ = env.wind_mps;
  wind_dir_deg_ = env.wind_dir_deg;
  gust_mps_ = env.gust_mps.value_or(wind_mps_ * config_.gust_factor);
}

PeerAnswer WeatherService::weather_update(const SelfView& self) const {
  std::string advisory = "ok";
  if (config_.no_fly_weather.count(weather_) != 0 || gust_mps_ >= config_.no_fly_gust_mps) {
    advisory = "no_fly";
  } else if (gust_mps_ >= config_.caution_gust_mps) {
    advisory = "caution";
  }
  PeerAnswer answer;
  answer.payload = {{"weather", weather_},
                    {"wind_mps", rounded(wind_mps_, 1)},
                    {"wind_dir_deg", rounded(wind_dir_deg_, 1)},
                    {"gust_mps", rounded(gust_mps_, 1)},
                    {"advisory", advisory},
                    {"time_s", rounded(self.now_s, 1)}};
  return answer;
}

}  // namespace a3::vehicle
