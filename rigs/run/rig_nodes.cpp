// Building a rig's nodes, whole or in parts.
#include "rigs/run/rig_nodes.hpp"

#include <filesystem>
#include <stdexcept>

#include "common/node_stats.hpp"

namespace a3::rigs {

std::vector<common::Node*> RigNodes::in_start_order() const {
  std::vector<common::Node*> out;
  if (recorder) out.push_back(recorder.get());
  if (log) out.push_back(log.get());
  for (const VehicleNodes& v : vehicles) {
    for (common::Node* n : v.in_start_order()) out.push_back(n);
  }
  if (conversation) out.push_back(conversation.get());
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
                        const Scenario& s, const std::vector<VehicleBuses>& buses, bool agent_in_thread) {
  if (buses.size() != cfg.vehicles.size()) {
    throw std::logic_error("make_rig_nodes: " + std::to_string(cfg.vehicles.size()) + " vehicles but " +
                           std::to_string(buses.size()) + " sets of buses");
  }
  RigNodes n;
  if (has_part(parts, RigPart::kGround)) {
    n.recorder = std::make_unique<EpisodeRecorderNode>(s.mission, cfg.agent_vehicle().vehicle_id(),
                                                       s.airspace.no_fly_zones);
    if (o.write_lcm_log) {
      std::filesystem::create_directories(o.out_dir);
      n.log = std::make_unique<LcmLogNode>(o.out_dir / "episode.lcmlog");
    }
    agent::ConversationConfig conv = cfg.conversation;
    conv.agent_runs_in_thread = agent_in_thread;
    n.conversation = std::make_unique<agent::ConversationNode>(conv, make_agent(o));
  }
  for (std::size_t i = 0; i < cfg.vehicles.size(); ++i) n.vehicles.push_back(make_vehicle(parts, cfg.vehicles[i], buses[i]));
  return n;
}

}  // namespace a3::rigs
