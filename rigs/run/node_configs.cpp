// Scenario → node configurations.
#include "rigs/run/node_configs.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

#include "agent/conversation/replay_agent.hpp"
#include "agent/conversation/scripted_agent.hpp"
#include "agent/conversation/think_time.hpp"
#include "agent/llm/llm_agent.hpp"
#include "common/json_file.hpp"
#include "dynamics/scenario_setup.hpp"
#include "linkemu/network_trace.hpp"
#include "rigs/run/fc_setup.hpp"
#include "rigs/run/llm_run.hpp"

namespace a3::rigs {
namespace {

linkemu::NetworkTrace trace_for(const linkemu::ScenarioNetwork& n, const std::filesystem::path& shared_dir) {
  std::filesystem::path p = n.trace;
  if (n.trace.rfind("alphabench:", 0) == 0) {
    p = n.trace.substr(11);
    if (p.is_relative()) p = shared_dir / "alphabench" / "eval_runs" / p;
  }
  return linkemu::load_network_trace(p, n.trace_period_s);
}

}  // namespace

VehicleConfigs make_vehicle_configs(const Scenario& s, const RunOptions& o, common::VehicleId id) {
  VehicleConfigs c;

  // Dynamics: the airframe with the scenario's payloads, wind, on the ground below the pose.
  c.dynamics.params = dynamics::airframe_by_name_or_path(s.airframe);
  dynamics::apply_flight_start(flight_start(s.start), true, c.dynamics);
  c.dynamics.turbulence.reference_altitude_m = std::max(10.0, s.mission.cruise_altitude_m);
  c.dynamics.integrator = o.integrator;
  c.dynamics.publish_rate_hz = o.dynamics_rate_hz;
  c.dynamics.seed = o.seed;
  // The payload within the airframe's lift was checked when the scenario loaded (scenario_checks).
  const dynamics::QuadrotorModel model(c.dynamics.params);

  // Bridge and flight controller.
  c.bridge.seed = o.seed;
  c.bridge.forward_sim_clock = o.runtime == Runtime::kReal && o.sync == Sync::kLockstep;
  // Only the commanders command: the fc obeys the bridge, the bridge takes ESC commands from the fc.
  c.fc.command_sources = {c.bridge.node_id};
  c.bridge.fc_node_id = c.fc.node_id;
  c.fc.params.vehicle = fc_vehicle_from_airframe(c.dynamics.params);
  c.fc.params.fence = geofence_from(s.start);
  c.fc.params.no_fly_zones = s.airspace.no_fly_zones;

  // Link emulator: the scenario's network.link settings, then its slice, trace and outages.
  c.link = s.network.link;
  c.link.seed = o.seed;
  c.link.initial_slice = o.slice ? *o.slice : linkemu::parse_slice(s.network.initial_slice);
  if (!s.network.trace.empty()) c.link.trace = trace_for(s.network, o.shared_dir);
  for (const auto& w : s.network.degradations) {
    c.link.forced_degradations.push_back({static_cast<int64_t>(w.start_s * 1e6),
                                          static_cast<int64_t>((w.start_s + w.duration_s) * 1e6)});
  }

  // Vehicle side.
  vehicle::ToolServerConfig& t = c.tool_server;
  t.airspace = s.airspace;
  t.home_W_m = s.mission.home_W_m;
  t.env = s.start.env;
  t.sensors = s.start.sensors;
  dynamics::RotorSpeeds hover;
  hover.fill(model.hover_speed_radps());
  t.energy.hover_power_w = model.electrical_power_W(hover);
  t.energy.battery_capacity_wh = model.battery_energy_J() / 3600.0;
  t.energy.cruise_speed_mps = s.mission.cruise_speed_mps;
  t.gate.return_altitude_m = c.fc.params.failsafe.return_altitude_m;
  t.gate.geofence_margin_m = std::max(t.gate.geofence_margin_m, c.fc.params.failsafe.fence_margin_m);
  t.gate.max_speed_mps = c.fc.params.limits.max_horizontal_speed_mps;
  t.airframe = {c.fc.params.vehicle.mass_kg, c.dynamics.params.aero.linear_drag_Ns_per_m,
                c.dynamics.params.aero.drag_cdA_m2, dynamics::kAirDensity_kgpm3, c.fc.params.limits.max_tilt_deg,
                c.fc.params.limits.max_horizontal_accel_mps2, c.fc.params.limits.max_horizontal_speed_mps};
  c.monitor.airspace = s.airspace;
  c.assign_vehicle(id);
  return c;
}

RigConfigs make_rig_configs(const Scenario& s, const RunOptions& o) {
  RigConfigs c;
  c.vehicles.push_back(make_vehicle_configs(s, o, 0));
  // Ground side.
  agent::ConversationConfig& v = c.conversation;
  v.vehicle = c.agent_vehicle().vehicle_id();
  v.mission = s.mission;
  v.initial_state = s.initial_state;
  v.airspace_brief = s.airspace_brief();
  v.min_turns = o.min_turns;
  v.max_turns = o.max_turns;
  return c;
}

std::unique_ptr<agent::Agent> make_agent(const RunOptions& o) {
  std::unique_ptr<agent::Agent> inner;
  if (o.agent_factory) {
    inner = o.agent_factory();
  } else if (o.agent == "scripted") {
    inner = std::make_unique<agent::ScriptedAgent>();
  } else if (o.agent.rfind("replay:", 0) == 0) {
    std::filesystem::path p = o.agent.substr(7);
    if (o.agent.rfind("replay:alphabench:", 0) == 0) {
      p = o.agent.substr(18);
      if (p.is_relative()) p = o.shared_dir / "alphabench" / "eval_runs" / p;
    }
    inner = std::make_unique<agent::ReplayAgent>(agent::ReplayAgent::from_file(p));
  } else if (o.agent == "llm") {
    inner = make_llm_agent(o);
  } else {
    throw std::invalid_argument("unknown agent '" + o.agent +
                                "' (scripted, llm, replay:<episode.json>, replay:alphabench:<path>)");
  }
  const agent::ThinkTime think = agent::ThinkTime::parse(o.think_time);
  if (think.is_zero()) return inner;
  return std::make_unique<agent::ThinkTimeAgent>(std::move(inner), think, o.seed);
}

}  // namespace a3::rigs
