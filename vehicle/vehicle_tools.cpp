// The vehicle's built-in tool handlers: every group, registered once.
#include "vehicle/vehicle_tools.hpp"

namespace a3::vehicle {

const ToolHandlers& vehicle_tools() {
  static const ToolHandlers handlers = [] {
    ToolHandlers h;
    add_query_tools(h);
    add_motion_tools(h);
    add_route_tools(h);
    add_payload_tools(h);
    add_peer_tasks(h);
    return h;
  }();
  return handlers;
}

}  // namespace a3::vehicle
