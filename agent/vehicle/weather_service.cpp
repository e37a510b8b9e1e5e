// The simulated weather service.
#include "agent/vehicle/weather_service.hpp"

#include <cmath>
#include <stdexcept>

#include "agent/vehicle/observation_json.hpp"

namespace a3::agent {
namespace {

double number(const nlohmann::json& env, const char* key, double fallback, bool non_negative) {
  if (!env.contains(key)) return fallback;
  const auto& v = env[key];
  if (!v.is_number() || !std::isfinite(v.get<double>()) || (non_negative && v.get<double>() < 0.0)) {
    throw std::invalid_argument(std::string("env.") + key + ": expected a finite number" +
                                (non_negative ? " >= 0" : ""));
  }
  return v.get<double>();
}

}  // namespace

void WeatherConfig::validate(const std::string& where) const {
  if (!std::isfinite(gust_factor) || gust_factor < 1.0) {
    throw std::invalid_argument(where + ".gust_factor must be >= 1, got " + std::to_string(gust_factor));
  }
  if (!std::isfinite(caution_gust_mps) || !std::isfinite(no_fly_gust_mps) || caution_gust_mps < 0.0 ||
      no_fly_gust_mps < caution_gust_mps) {
    throw std::invalid_argument(where + ".caution_gust_mps and no_fly_gust_mps must satisfy 0 <= caution <= no_fly");
  }
}

WeatherService::WeatherService(const nlohmann::json& env, WeatherConfig config) : config_(std::move(config)) {
  config_.validate("weather");
  if (env.is_null()) return;
  if (!env.is_object()) throw std::invalid_argument("env: expected an object");
  if (env.contains("weather")) {
    if (!env["weather"].is_string()) throw std::invalid_argument("env.weather: expected a string");
    weather_ = env["weather"].get<std::string>();
  }
  wind_mps_ = number(env, "wind_mps", 0.0, true);
  wind_dir_deg_ = number(env, "wind_dir_deg", 0.0, false);
  gust_mps_ = number(env, "gust_mps", wind_mps_ * config_.gust_factor, true);
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

}  // namespace a3::agent
