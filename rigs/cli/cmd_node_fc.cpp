// `a3rig node fc`: the flight controller as its own real-time process on a CAN bus. It sees the
// vehicle only through DroneCAN frames (sensors in, esc.RawCommand out, a3.fc.Command in,
// a3.fc.Status out) and does not use LCM at all, so a real autopilot could take its place.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/nodes/command_sources.hpp"
#include "bridge/nodes/fc_node.hpp"
#include "common/json_file.hpp"
#include "common/no_fly_zone.hpp"
#include "common/runtime.hpp"
#include "dynamics/vehicle_params.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/node_thread_loop.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/run/fc_setup.hpp"
#include "rigs/scenario/scenario_airspace.hpp"

namespace a3::rigs {
namespace {

struct FcArgs {
  std::string can = "vcan0";
  std::string params;
  std::string airframe;
  std::string scenario;
  std::string home;
  int node_id = bridge::kDefaultFcNodeId;
  std::vector<int> command_sources{bridge::kDefaultBridgeNodeId};
  bool no_step_on_command = false;
  NodePacing pacing;
};

// An a3rig scenario's no-fly zones (its top-level "airspace"); none in an episode or an
// initial_state.
std::vector<common::NoFlyZone> no_fly_zones_of_file(const std::string& path, const InitialState& state) {
  const nlohmann::json doc = common::load_json_file(path);
  if (!doc.is_object() || !doc.contains("airspace")) return {};
  return parse_airspace(state, doc["airspace"], path + ": /airspace").no_fly_zones;
}

bridge::FcNodeConfig fc_config_from(const FcArgs& args) {
  bridge::FcNodeConfig config;
  dynamics::VehicleParams vehicle =
      args.airframe.empty() ? dynamics::default_vehicle_params() : dynamics::airframe_by_name_or_path(args.airframe);
  if (!args.scenario.empty()) {
    const InitialState state = load_initial_state_file(args.scenario);
    vehicle = dynamics::with_payloads(vehicle, state.payloads);
    config.params.fence = geofence_from(state);
    config.params.no_fly_zones = no_fly_zones_of_file(args.scenario, state);
  }
  config.params.vehicle = fc_vehicle_from_airframe(vehicle);
  if (!args.params.empty()) {
    config.params = bridge::fc_params_from_json(common::load_json_file(args.params), args.params, config.params);
  }
  if (!args.home.empty()) config.home = parse_home(args.home);
  config.node_id = static_cast<uint8_t>(args.node_id);
  config.command_sources.assign(args.command_sources.begin(), args.command_sources.end());
  config.step_on_command = !args.no_step_on_command;
  return config;
}

void report(const bridge::FcNode& node, const bridge::CanBus& can, double sim_s) {
  const bridge::FlightStatus s = node.status_snapshot();
  const auto cs = can.stats();
  std::fprintf(stderr,
               "t=%8.1f s  %-11s %s failsafe %-11s p=(%.1f, %.1f, %.1f) m  battery %.0f %%  %s  "
               "CAN sent %llu received %llu refused %llu\n",
               sim_s, bridge::to_string(s.mode), s.armed ? "armed   " : "disarmed", bridge::to_string(s.failsafe),
               s.p_W_m.x(), s.p_W_m.y(), s.p_W_m.z(), s.battery_pct, common::to_text(node.counters()).c_str(),
               static_cast<unsigned long long>(cs.frames_sent), static_cast<unsigned long long>(cs.frames_received),
               static_cast<unsigned long long>(cs.send_refused));
}

int run_fc(const FcArgs& args) {
  const bridge::FcNodeConfig config = fc_config_from(args);
  const common::WallClock clock(args.pacing.rtf);
  std::unique_ptr<bridge::CanBus> can = bridge::open_can_bus(args.can);
  bridge::FcNode node(*can, config);
  // The fc speaks only CAN; the node runtime's bus is an in-process LCM nobody else sees.
  common::RealTimeNodeThread thread(node, clock, "memq://");
  std::fprintf(stderr,
               "a3rig node fc: node %d on %s, control %.0f Hz, status %.0f Hz, vehicle %.2f kg, home %.6f, %.6f, "
               "%.1f m, commands from node(s) %s, real-time factor %g\n",
               args.node_id, can->name().c_str(), config.params.control_rate_hz, config.params.status_rate_hz,
               config.params.vehicle.mass_kg, config.home.latitude_deg, config.home.longitude_deg,
               config.home.height_m, bridge::command_sources_text(config.command_sources).c_str(), args.pacing.rtf);
  const std::string failure = run_node_thread(thread, clock, args.pacing.duration_s, args.pacing.report_every_s,
                                              [&](double sim_s) { report(node, *can, sim_s); });
  node.stop();
  if (!failure.empty()) {
    std::cerr << "a3rig node fc: stopped by an error: " << failure << "\n";
    return 1;
  }
  const auto lateness = thread.executor().lateness_samples_us();
  if (!lateness.empty()) {
    std::vector<double> sorted = lateness;
    std::sort(sorted.begin(), sorted.end());
    std::fprintf(stderr, "a3rig node fc: timer lateness p50 %.0f us, p99 %.0f us, max %.0f us\n",
                 sorted[sorted.size() / 2], sorted[sorted.size() * 99 / 100], sorted.back());
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("52-node-fc", [](CLI::App& app) {
  auto args = std::make_shared<FcArgs>();
  CLI::App* node = app.get_subcommand("node");
  CLI::App* cmd = node->add_subcommand(
      "fc",
      "Run the flight controller in real time on a CAN bus (DroneCAN): sensor messages in, "
      "esc.RawCommand out at the control rate, a3.fc.Command in, a3.fc.Status out, NodeStatus at 1 Hz. "
      "Pair it with `a3rig node bridge` on the same bus. Stops on Ctrl-C or after --duration-s.");
  cmd->add_option("--can", args->can,
                  "CAN bus: an interface name (SocketCAN when it exists, else the userspace bus of that name), "
                  "socketcan:NAME or userspace:NAME (default vcan0)");
  cmd->add_option("--params", args->params, "flight-controller parameter JSON (bridge/fc/README.md)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--airframe", args->airframe,
                  "the vehicle the fc is tuned for: a built-in airframe (iris, the default, or heavy-lift) or an "
                  "airframe JSON file; --params' vehicle section overrides it");
  cmd->add_option("--scenario", args->scenario,
                  "a3rig scenario, α³-Bench episode or initial_state JSON: payload mass, geofence and altitude "
                  "bounds, and a scenario's no-fly zones (the fc brakes before them)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--home", args->home, "ENU origin LAT,LON,HEIGHT (default 47.397742,8.545594,488); "
                                        "give the bridge the same one");
  cmd->add_option("--node-id", args->node_id, "DroneCAN node ID (default 10)")->check(a3::rigs::between(1, 127));
  cmd->add_option("--command-sources", args->command_sources,
                  "node IDs whose a3.fc.Command (and a3.sim.Clock) the fc obeys, comma-separated: the bridge's and, "
                  "where one is on the bus, a ground station's (default 20, the bridge). Commands from any other "
                  "node are refused, counted (commands_rejected_source) and reported in a3.fc.CommandRefused, at "
                  "most once a second. CAN has no authentication: see bridge/README.md")
      ->delimiter(',')
      ->check(a3::rigs::between(1, 127));
  cmd->add_flag("--no-step-on-command", args->no_step_on_command,
                "do not run a control step at once when a command is accepted (wait for the next tick)");
  add_node_pacing_flags(*cmd, args->pacing);
  cmd->callback([args] { command_exit_status() = run_fc(*args); });
});

}  // namespace a3::rigs
