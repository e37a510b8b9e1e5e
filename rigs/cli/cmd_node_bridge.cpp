// `a3rig node bridge`: the LCM⇄CAN bridge as its own real-time process: the vehicle's sensors
// (from A3_STATE, with seeded noise) and ESCs (to A3_ACTUATORS) on a DroneCAN bus, and the
// ground's commands (A3_FC_CMD) and the fc's status (A3_FC_STATUS) between LCM and CAN.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/sim/bridge_node.hpp"
#include "common/runtime.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/node_thread_loop.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/run/fc_setup.hpp"

namespace a3::rigs {
namespace {

struct BridgeArgs {
  std::string can = "vcan0";
  std::string home;
  uint64_t seed = 1;
  int node_id = bridge::kDefaultBridgeNodeId;
  int fc_node_id = bridge::kDefaultFcNodeId;
  bridge::SensorRates rates;
  std::string lcm_url;
  NodePacing pacing;
};

void report(const bridge::BridgeNode& node, const bridge::CanBus& can, double sim_s) {
  const auto cs = can.stats();
  std::fprintf(stderr, "t=%8.1f s  %s  CAN sent %llu received %llu refused %llu\n", sim_s,
               common::to_text(node.counters()).c_str(), static_cast<unsigned long long>(cs.frames_sent),
               static_cast<unsigned long long>(cs.frames_received), static_cast<unsigned long long>(cs.send_refused));
}

int run_bridge(const BridgeArgs& args) {
  bridge::BridgeNodeConfig config;
  if (!args.home.empty()) config.home = parse_home(args.home);
  config.seed = args.seed;
  config.node_id = static_cast<uint8_t>(args.node_id);
  config.fc_node_id = static_cast<uint8_t>(args.fc_node_id);
  config.rates = args.rates;
  const common::WallClock clock(args.pacing.rtf);
  std::unique_ptr<bridge::CanBus> can = bridge::open_can_bus(args.can);
  bridge::BridgeNode node(*can, config);
  common::RealTimeNodeThread thread(node, clock, args.lcm_url);
  thread.bus().check_loopback();
  std::fprintf(stderr,
               "a3rig node bridge: node %d on %s, LCM %s, IMU %.0f Hz (at most one per state), GNSS %.0f Hz, "
               "baro %.0f Hz, mag %.0f Hz, battery %.0f Hz, seed %llu, real-time factor %g\n",
               args.node_id, can->name().c_str(), thread.bus().url().c_str(), args.rates.imu_hz, args.rates.gnss_hz,
               args.rates.baro_hz, args.rates.mag_hz, args.rates.battery_hz,
               static_cast<unsigned long long>(args.seed), args.pacing.rtf);
  const std::string failure = run_node_thread(thread, clock, args.pacing.duration_s, args.pacing.report_every_s,
                                              [&](double sim_s) { report(node, *can, sim_s); });
  node.stop();
  if (!failure.empty()) {
    std::cerr << "a3rig node bridge: stopped by an error: " << failure << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("51-node-bridge", [](CLI::App& app) {
  auto args = std::make_shared<BridgeArgs>();
  CLI::App* node = app.get_subcommand("node");
  CLI::App* cmd = node->add_subcommand(
      "bridge",
      "Run the LCM<->CAN bridge in real time: A3_STATE -> DroneCAN sensor messages (IMU, GNSS, baro, "
      "magnetometer, battery, with seeded noise), esc.RawCommand -> A3_ACTUATORS, A3_FC_CMD -> a3.fc.Command "
      "(heartbeats only when the ground sends them), a3.fc.Status -> A3_FC_STATUS, a3.fc.CommandRefused -> "
      "A3_SAFETY (command_refused). Stops on Ctrl-C or after --duration-s.");
  cmd->add_option("--can", args->can,
                  "CAN bus: an interface name (SocketCAN when it exists, else the userspace bus of that name), "
                  "socketcan:NAME or userspace:NAME (default vcan0)");
  cmd->add_option("--home", args->home, "ENU origin LAT,LON,HEIGHT (default 47.397742,8.545594,488); "
                                        "give the fc the same one");
  cmd->add_option("--seed", args->seed, "seed of the sensor noise (default 1)");
  cmd->add_option("--node-id", args->node_id, "DroneCAN node ID (default 20)")->check(a3::rigs::between(1, 127));
  cmd->add_option("--fc-node-id", args->fc_node_id,
                  "the flight controller's node ID: the only node whose esc.RawCommand and a3.fc.Status the bridge "
                  "takes; others are refused, counted (rejected_source) and reported on A3_SAFETY (default 10)")
      ->check(CLI::Range(1, 127));
  cmd->add_option("--imu-rate-hz", args->rates.imu_hz, "IMU report rate; never above the state rate (default 200)")
      ->check(a3::rigs::between(1.0, 10000.0));
  cmd->add_option("--gnss-rate-hz", args->rates.gnss_hz, "GNSS rate (default 10)")->check(a3::rigs::between(0.1, 1000.0));
  cmd->add_option("--baro-rate-hz", args->rates.baro_hz, "barometer rate (default 50)")->check(a3::rigs::between(0.1, 1000.0));
  cmd->add_option("--mag-rate-hz", args->rates.mag_hz, "magnetometer rate (default 50)")->check(a3::rigs::between(0.1, 1000.0));
  cmd->add_option("--battery-rate-hz", args->rates.battery_hz, "battery rate (default 5)")
      ->check(a3::rigs::between(0.1, 1000.0));
  add_lcm_url_flag(*cmd, args->lcm_url);
  add_node_pacing_flags(*cmd, args->pacing);
  cmd->callback([args] { command_exit_status() = run_bridge(*args); });
});

}  // namespace a3::rigs
