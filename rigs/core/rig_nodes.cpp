// Building a rig's nodes, whole or in parts.
#include "rigs/core/rig_nodes.hpp"

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <stdexcept>

namespace a3::rigs {
namespace {

nlohmann::json direction_json(const linkemu::DirectionStats& d) {
  nlohmann::json dropped = nlohmann::json::object();
  for (std::size_t r = 0; r < linkemu::kDropReasonCount; ++r) {
    dropped[linkemu::to_string(static_cast<linkemu::DropReason>(r))] = d.dropped[r];
  }
  return {{"received", d.received}, {"delivered", d.delivered}, {"lost", d.lost}, {"dropped", dropped},
          {"bytes_delivered", d.bytes_delivered}};
}

bool has(const std::vector<RigPart>& parts, RigPart p) { return std::find(parts.begin(), parts.end(), p) != parts.end(); }

}  // namespace

const std::vector<RigPart>& rig_parts_outside_ground() {
  static const std::vector<RigPart> parts = {RigPart::kDynamics, RigPart::kBridge, RigPart::kFc, RigPart::kLinkemu,
                                             RigPart::kVehicle};
  return parts;
}

std::string to_string(RigPart part) {
  switch (part) {
    case RigPart::kGround: return "ground";
    case RigPart::kDynamics: return "dynamics";
    case RigPart::kBridge: return "bridge";
    case RigPart::kFc: return "fc";
    case RigPart::kLinkemu: return "linkemu";
    case RigPart::kVehicle: return "vehicle";
  }
  return "?";
}

RigPart parse_rig_part(const std::string& name) {
  for (RigPart p : {RigPart::kGround, RigPart::kDynamics, RigPart::kBridge, RigPart::kFc, RigPart::kLinkemu,
                    RigPart::kVehicle}) {
    if (to_string(p) == name) return p;
  }
  throw std::invalid_argument("unknown rig part '" + name + "' (ground, dynamics, bridge, fc, linkemu, vehicle)");
}

std::vector<common::Node*> RigNodes::in_start_order() const {
  std::vector<common::Node*> out;
  for (common::Node* n : std::initializer_list<common::Node*>{recorder.get(), log.get(), dynamics.get(), bridge.get(),
                                                             fc.get(), link.get(), tools.get(), monitor.get(),
                                                             conversation.get()}) {
    if (n != nullptr) out.push_back(n);
  }
  return out;
}

nlohmann::json RigNodes::counters() const {
  nlohmann::json out = nlohmann::json::object();
  if (dynamics) {
    const auto d = dynamics->counters();
    out["dynamics"] = {{"steps", d.steps}, {"commands", d.commands_received}, {"rejected", d.commands_rejected},
                       {"clamped", d.commands_clamped}, {"stale_steps", d.stale_steps}};
  }
  if (conversation) {
    const auto c = conversation->counters();
    out["conversation"] = {{"actions_sent", c.actions_sent}, {"observations", c.observations}, {"timeouts", c.timeouts},
                           {"stale_observations", c.stale_observations}, {"heartbeats", c.heartbeats}};
  }
  if (tools) {
    const auto t = tools->counters();
    out["tool_server"] = {{"link_messages", t.link_messages}, {"malformed_dropped", t.malformed_dropped},
                          {"mcp_calls", t.mcp_calls}, {"a2a_messages", t.a2a_messages}, {"errors", t.errors},
                          {"gate_refusals", t.gate_refusals}, {"fc_commands", t.fc_commands},
                          {"fc_refusals", t.fc_refusals}, {"timeouts", t.timeouts},
                          {"routes_completed", t.routes_completed}, {"images_captured", t.images_captured},
                          {"image_bytes_downlinked", t.image_bytes_downlinked}};
  }
  if (link) {
    out["link"] = {{"up", direction_json(link->stats().up)}, {"down", direction_json(link->stats().down)},
                   {"slice_switch_requests", link->stats().slice_switch_requests}};
  }
  if (recorder) out["lcm_log_events"] = log ? log->events() : 0;
  return out;
}

RigNodes make_rig_nodes(const std::vector<RigPart>& parts, const RigConfigs& cfg, const RunOptions& o,
                        const Scenario& s, const RigNodeBuses& buses, bool agent_in_thread) {
  RigNodes n;
  if (has(parts, RigPart::kGround)) {
    n.recorder = std::make_unique<EpisodeRecorderNode>(s.mission);
    if (o.write_lcm_log) {
      std::filesystem::create_directories(o.out_dir);
      n.log = std::make_unique<LcmLogNode>(o.out_dir / "episode.lcmlog");
    }
    agent::ConversationConfig conv = cfg.conversation;
    conv.agent_runs_in_thread = agent_in_thread;
    n.conversation = std::make_unique<agent::ConversationNode>(conv, make_agent(o));
  }
  if (has(parts, RigPart::kDynamics)) n.dynamics = std::make_unique<dynamics::DynamicsNode>(cfg.dynamics);
  if (has(parts, RigPart::kBridge)) {
    if (buses.can_bridge == nullptr) throw std::logic_error("make_rig_nodes: the bridge needs a CAN bus");
    n.bridge = std::make_unique<bridge::BridgeNode>(*buses.can_bridge, cfg.bridge);
  }
  if (has(parts, RigPart::kFc)) {
    if (buses.can_fc == nullptr) throw std::logic_error("make_rig_nodes: the flight controller needs a CAN bus");
    n.fc = std::make_unique<bridge::FcNode>(*buses.can_fc, cfg.fc);
  }
  if (has(parts, RigPart::kLinkemu)) n.link = std::make_unique<linkemu::LinkEmulatorNode>(cfg.link);
  if (has(parts, RigPart::kVehicle)) {
    n.tools = std::make_unique<agent::ToolServerNode>(cfg.tool_server);
    n.monitor = std::make_unique<agent::AirspaceMonitorNode>(cfg.monitor);
  }
  return n;
}

}  // namespace a3::rigs
