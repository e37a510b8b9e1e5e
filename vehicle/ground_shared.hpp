// What the vehicle side shares with the ground side (agent/): the airspace the scenario declares,
// the link protocol's envelopes and the tool catalog. Named here once for vehicle/.
#pragma once

#include "agent/airspace.hpp"
#include "agent/link_protocol.hpp"
#include "agent/tool_catalog.hpp"

namespace a3::vehicle {

using agent::Airspace;
using agent::NoFlyZone;
using agent::TrafficPlan;
using agent::TrafficWaypoint;

using agent::ActionEnvelope;
using agent::decode_action;
using agent::encode_observation;
using agent::kMaxLinkJsonBytes;
using agent::ObservationEnvelope;

using agent::A2aTaskSpec;
using agent::CallAsAction;
using agent::FunctionSpec;
using agent::McpToolSpec;
using agent::ToolCatalog;
using agent::TurnCallSpec;

}  // namespace a3::vehicle
