// Tool server configuration checks.
#include "vehicle/tool_server_config.hpp"

#include <cmath>
#include <stdexcept>

#include "common/config_checks.hpp"

namespace a3::vehicle {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

using common::require_positive;

}  // namespace

void RouteConfig::validate(const std::string& where) const {
  require_positive(arrive_tolerance_m, where + ".arrive_tolerance_m");
  require_positive(orbit_max_chord_m, where + ".orbit_max_chord_m");
  require_positive(default_survey_spacing_m, where + ".default_survey_spacing_m");
  require(max_waypoints >= 1, where + ".max_waypoints must be >= 1");
}

void ToolServerConfig::validate() const {
  const std::string w = "ToolServerConfig";
  require(home_W_m.allFinite(), w + ".home_W_m must be finite");
  require(airspace.min_altitude_m <= airspace.max_altitude_m, w + ".airspace: min_altitude_m " +
                                                                  std::to_string(airspace.min_altitude_m) +
                                                                  " is above max_altitude_m " +
                                                                  std::to_string(airspace.max_altitude_m));
  require(airspace.geofence.empty() || airspace.geofence.size() >= 3,
          w + ".airspace.geofence needs at least 3 vertices (or none for no geofence)");
  for (std::size_t i = 0; i < airspace.no_fly_zones.size(); ++i) {
    const auto& z = airspace.no_fly_zones[i];
    const std::string where = w + ".airspace.no_fly_zones[" + std::to_string(i) + "]";
    require(!z.id.empty(), where + ".id must not be empty");
    require(z.floor_m <= z.ceiling_m, where + ".floor_m must not be above ceiling_m");
    if (z.polygon.empty()) {
      require_positive(z.radius_m, where + ".radius_m");
      require(z.centre.allFinite(), where + ".centre must be finite");
    } else {
      require(z.polygon.size() >= 3, where + ".polygon needs at least 3 vertices");
    }
  }
  energy.validate(w + ".energy");
  gate.validate(w + ".gate");
  images.validate(w + ".images");
  swarm.validate(w + ".swarm");
  weather.validate(w + ".weather");
  planner.validate(w + ".planner");
  route.validate(w + ".route");
  require_positive(fc_status_timeout_s, w + ".fc_status_timeout_s");
  require_positive(slice_reply_timeout_s, w + ".slice_reply_timeout_s");
  require_positive(traffic_rate_hz, w + ".traffic_rate_hz");
  require(max_queued_actions >= 1, w + ".max_queued_actions must be >= 1");
  require(!sender.empty(), w + ".sender must not be empty");
}

}  // namespace a3::vehicle
