// The vehicle's built-in tool handlers, grouped by kind; each group registers its handlers by
// their catalog names (agent/tool_catalog.json).
#pragma once

#include "vehicle/tool_handlers.hpp"

namespace a3::vehicle {

void add_motion_tools(ToolHandlers& handlers);    // takeoff, set_waypoint, set_altitude, navigate_to,
                                                  // adjust_speed, hold, land (motion_tools.cpp)
void add_route_tools(ToolHandlers& handlers);     // execute_maneuver, return_to_home (route_tools.cpp)
void add_query_tools(ToolHandlers& handlers);     // read_telemetry, check_geofence (query_tools.cpp)
void add_payload_tools(ToolHandlers& handlers);   // activate_sensor, capture_image,
                                                  // switch_network_slice (payload_tools.cpp)
void add_peer_tasks(ToolHandlers& handlers);      // the A2A tasks (peer_tasks.cpp)

// All of the above, built once.
const ToolHandlers& vehicle_tools();

}  // namespace a3::vehicle
