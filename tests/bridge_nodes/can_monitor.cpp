// The frame monitor of the real-vcan closed-loop test (scripts/vcan-vm/closed-loop-test.sh):
// a third, passive DroneCAN node on the bus that decodes every transfer, counts them by type
// and source, and on SIGTERM/SIGINT (or after --duration-s of wall time) prints what it saw and
// checks it: ESC commands from the fc at >= 200 Hz of simulated time, sensors from the bridge
// at their rates, commands and status both ways, NodeStatus from both nodes, no rejected frames.
// Exits 0 when all checks hold, 1 otherwise.
#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/node.hpp"
#include "common/realtime_executor.hpp"
#include "rigs/cli/signal_stop.hpp"

namespace {

using namespace a3::bridge;

struct Seen {
  uint64_t count = 0;
  int64_t first_us = -1, last_us = -1;
  // Transfers per simulated second between the first and the last one.
  double rate_hz(double rtf) const {
    return count > 1 ? (count - 1) / ((last_us - first_us) * 1e-6 * rtf) : 0.0;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Passive DroneCAN frame monitor for the real-vcan closed-loop test"};
  std::string can_spec = "socketcan:vcan0";
  double rtf = 1.0, duration_s = 0.0;
  int fc_node = 10, bridge_node = 20;
  app.add_option("--can", can_spec, "CAN bus");
  app.add_option("--rtf", rtf, "real-time factor of the rig (rates are reported in simulated time)");
  app.add_option("--duration-s", duration_s, "stop after this much wall time (0: on SIGTERM)");
  CLI11_PARSE(app, argc, argv);

  std::unique_ptr<CanBus> can;
  try {
    can = open_can_bus(can_spec);
  } catch (const std::exception& e) {
    std::printf("monitor: cannot open %s: %s\n", can_spec.c_str(), e.what());
    return 1;
  }
  const a3::common::WallClock clock(1.0);  // wall time: rates are scaled by --rtf
  a3::common::RealTimeExecutor executor(clock);
  DroneCanNode node(*can, DroneCanNodeConfig{127, {}, 500'000});  // listens only, never sends
  std::map<std::pair<std::string, int>, Seen> seen;
  auto record = [&](const char* type, const ReceivedTransfer& t) {
    Seen& s = seen[{type, t.header.source_node_id}];
    ++s.count;
    const int64_t now = clock.now_us();
    if (s.first_us < 0) s.first_us = now;
    s.last_us = now;
  };
  uint64_t esc_spinning = 0;
  node.subscribe<EscRawCommand>([&](const EscRawCommand& m, const ReceivedTransfer& t) {
    record("esc.RawCommand", t);
    for (int16_t v : m.cmd) {
      if (v > 0) {
        ++esc_spinning;
        break;
      }
    }
  });
  node.subscribe<AhrsRawImu>([&](const AhrsRawImu&, const ReceivedTransfer& t) { record("ahrs.RawIMU", t); });
  node.subscribe<GnssFix2>([&](const GnssFix2&, const ReceivedTransfer& t) { record("gnss.Fix2", t); });
  node.subscribe<StaticPressure>([&](const StaticPressure&, const ReceivedTransfer& t) {
    record("air_data.StaticPressure", t);
  });
  node.subscribe<MagneticFieldStrength2>([&](const MagneticFieldStrength2&, const ReceivedTransfer& t) {
    record("ahrs.MagneticFieldStrength2", t);
  });
  node.subscribe<BatteryInfo>([&](const BatteryInfo&, const ReceivedTransfer& t) { record("power.BatteryInfo", t); });
  node.subscribe<FcCommand>([&](const FcCommand&, const ReceivedTransfer& t) { record("a3.fc.Command", t); });
  node.subscribe<FcStatus>([&](const FcStatus&, const ReceivedTransfer& t) { record("a3.fc.Status", t); });
  node.subscribe<NodeStatus>([&](const NodeStatus&, const ReceivedTransfer& t) { record("NodeStatus", t); });
  node.start(executor);
  a3::rigs::install_stop_signals();
  std::thread watcher([&] {
    while (!a3::rigs::stop_requested() && !(duration_s > 0 && clock.now_s() >= duration_s)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    executor.stop();
  });
  executor.run();
  watcher.join();
  node.stop();

  bool ok = true;
  const auto check = [&](const char* type, int source, double min_rate_hz, double max_rate_hz) {
    const Seen s = seen[{type, source}];
    const double rate = s.rate_hz(rtf);
    const bool good = s.count > 0 && rate >= min_rate_hz && rate <= max_rate_hz;
    std::printf("monitor: %-28s from node %3d: %7llu transfers, %7.1f /s simulated (expected %g..%g) %s\n", type,
                source, static_cast<unsigned long long>(s.count), rate, min_rate_hz, max_rate_hz,
                good ? "ok" : "WRONG");
    ok &= good;
  };
  check("esc.RawCommand", fc_node, 200.0, 260.0);
  check("a3.fc.Status", fc_node, 9.0, 15.0);
  check("NodeStatus", fc_node, 0.8, 1.3);
  check("ahrs.RawIMU", bridge_node, 180.0, 210.0);
  check("gnss.Fix2", bridge_node, 9.0, 11.0);
  check("air_data.StaticPressure", bridge_node, 45.0, 55.0);
  check("ahrs.MagneticFieldStrength2", bridge_node, 45.0, 55.0);
  check("power.BatteryInfo", bridge_node, 4.5, 5.5);
  check("a3.fc.Command", bridge_node, 4.0, 10.0);  // 5 Hz heartbeats and the mission's commands
  check("NodeStatus", bridge_node, 0.8, 1.3);
  const auto rs = node.reassembler_stats();
  const CanBusStats cs = can->stats();
  std::printf("monitor: %llu frames received, %llu rejected, %llu transfers expired, %llu kernel drops; "
              "%llu ESC commands with spinning rotors\n",
              static_cast<unsigned long long>(cs.frames_received), static_cast<unsigned long long>(rs.rejected_frames()),
              static_cast<unsigned long long>(rs.expired_transfers), static_cast<unsigned long long>(cs.receive_overruns),
              static_cast<unsigned long long>(esc_spinning));
  ok &= rs.rejected_frames() == 0 && cs.receive_overruns == 0 && esc_spinning > 0;
  std::printf("monitor: %s\n", ok ? "all checks passed" : "SOME CHECKS FAILED");
  return ok ? 0 : 1;
}
