// The weather service's configuration: env parsing and range checks.
#include "vehicle/weather_config.hpp"

#include <cmath>
#include <stdexcept>

#include "common/json_file.hpp"

namespace a3::vehicle {
namespace {

using common::InputError;

double finite_number(const nlohmann::json& object, const char* key, const std::string& where) {
  const double v = common::require_number(object, key, where);
  if (!std::isfinite(v)) throw InputError(where + "/" + key + ": must be a finite number");
  return v;
}

bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

void WeatherEnv::validate(const std::string& where) const {
  if (!finite_non_negative(wind_mps)) throw std::invalid_argument(where + ".wind_mps: expected a finite number >= 0");
  if (!std::isfinite(wind_dir_deg)) throw std::invalid_argument(where + ".wind_dir_deg: expected a finite number");
  if (gust_mps && !finite_non_negative(*gust_mps)) {
    throw std::invalid_argument(where + ".gust_mps: expected a finite number >= 0");
  }
}

void WeatherConfig::validate(const std::string& where) const {
  if (!std::isfinite(gust_factor) || gust_factor < 1.0) {
    throw std::invalid_argument(where + ".gust_factor must be >= 1, got " + std::to_string(gust_factor));
  }
  if (!std::isfinite(caution_gust_mps) || !std::isfinite(no_fly_gust_mps) || caution_gust_mps < 0.0 ||
      no_fly_gust_mps < caution_gust_mps) {
    throw std::invalid_argument(where + ".caution_gust_mps and no_fly_gust_mps must satisfy 0 <= caution <= no_fly");
  }
}

WeatherEnv parse_weather_env(const nlohmann::json& env, std::string_view json_path) {
  const std::string w(json_path);
  if (!env.is_object()) throw InputError(w + ": expected an object, got " + std::string(env.type_name()));
  WeatherEnv out;
  out.weather = common::require_string(env, "weather", w);
  out.wind_mps = finite_number(env, "wind_mps", w);
  out.wind_dir_deg = finite_number(env, "wind_dir_deg", w);
  if (out.wind_mps < 0.0) throw InputError(w + "/wind_mps: must be >= 0");
  if (env.contains("gust_mps")) {
    out.gust_mps = finite_number(env, "gust_mps", w);
    if (*out.gust_mps < 0.0) throw InputError(w + "/gust_mps: must be >= 0");
  }
  return out;
}

}  // namespace a3::vehicle
