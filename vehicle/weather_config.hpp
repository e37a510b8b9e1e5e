// What the weather service is configured from: the scenario's initial_state.env as a typed
// WeatherEnv (parsed here, once, by parse_weather_env) and the service's own thresholds
// (WeatherConfig: gust factor and advisory levels).
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <set>
#include <string>
#include <string_view>

namespace a3::vehicle {

// initial_state.env: the weather as reported at the start. Also what the dynamics' steady
// wind is set from (the orchestrator reads wind_mps and wind_dir_deg from it).
struct WeatherEnv {
  std::string weather = "clear";
  double wind_mps = 0.0;
  double wind_dir_deg = 0.0;       // where the wind blows from, degrees (corpus convention)
  std::optional<double> gust_mps;  // absent: the weather service's gust factor applies

  // Throws std::invalid_argument naming the field ("env.wind_mps: expected a finite number >= 0").
  void validate(const std::string& where) const;
};

struct WeatherConfig {
  double gust_factor = 1.4;  // gust = wind × this when env has no gust_mps
  double caution_gust_mps = 10.0;
  double no_fly_gust_mps = 15.0;
  std::set<std::string> no_fly_weather = {"thunderstorm", "storm", "hail", "heavy_snow"};

  void validate(const std::string& where) const;
};

// Parses an env object {"weather", "wind_mps", "wind_dir_deg"[, "gust_mps"]} (the first three
// required, numbers finite, speeds >= 0). `json_path` names where it is
// ("file.json: /initial_state/env"); throws common::InputError naming the path and field.
WeatherEnv parse_weather_env(const nlohmann::json& env, std::string_view json_path);

}  // namespace a3::vehicle
