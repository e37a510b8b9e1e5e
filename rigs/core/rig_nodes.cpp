// Building a rig's nodes, whole or in parts.
#include "rigs/core/rig_nodes.hpp"

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <stdexcept>

#include "common/node_stats.hpp"

namespace a3::rigs {
namespace {

bool has(const std::vector<RigPart>& parts, RigPart p) { return std::find(parts.begin(), parts.end(), p) != parts.end(); }

}  // namespace

const std::vector<RigPart>& rig_parts_outside_ground() {
  static const std::vector<RigPart> parts = {RigPart::kDynamics, RigPart::kBridge, RigPart::kFc, RigPart::kLinkemu,
                                             RigPart::kVehicle};
  return parts;
}

std::vector<RigPart> all_rig_parts() {
  std::vector<RigPart> parts = rig_parts_outside_ground();
  parts.insert(parts.begin(), RigPart::kGround);
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
  for (const common::Node* node : in_start_order()) {
    const nlohmann::json c = common::node_stats_json(node->counters(), {})["counters"];
    if (!c.empty()) out[node->name()] = c;
  }
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
