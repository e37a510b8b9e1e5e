// The world of a scenario as the episode report draws it: geofence, no-fly zones (polygons and
// cylinders with floor and ceiling), objectives, home, the other aircraft's planned tracks, the
// forced link degradations and the altitude envelope. Plain JSON for the page's script.
#pragma once

#include <nlohmann/json.hpp>

#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// {"geofence": [[x, y]...], "zones": [{"id", "polygon": [[x, y]...] (empty: a cylinder),
//  "centre": [x, y], "radius_m", "floor_m", "ceiling_m" (null: unbounded)}], "objectives": [{"id",
//  "type", "point": [x, y] or null, "radius_m", "area": [[x, y]...]}], "home": [x, y],
//  "peers": [{"id", "path": [[t_s, x, y, z]...], "min_separation_m"}],
//  "degradations": [[start_s, duration_s]...], "alt_bounds": [min_m or null, max_m or null]}.
nlohmann::json report_world_json(const Scenario& scenario);

}  // namespace a3::rigs
