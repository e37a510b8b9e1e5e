// `a3rig node part NAME`: one part of a rig (dynamics, bridge, fc, linkemu or vehicle) built
// from a scenario and run options exactly as `a3rig run` builds it, as a process of its own.
// `a3rig run --processes` starts these; they say "ready" on stdout once built and start on
// "go <CLOCK_MONOTONIC ns>" read from stdin (the epoch every process of the run shares), or
// at once with --start-now. They run until SIGINT/SIGTERM or until a node fails (exit 1).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "bridge/can/can_bus_factory.hpp"
#include "common/clock.hpp"
#include "common/runtime.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/run_flag_options.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/rig_nodes.hpp"
#include "rigs/run/rig_threads.hpp"
#include "rigs/scenario/shared_dir.hpp"

namespace a3::rigs {
namespace {

struct PartArgs {
  std::string part;
  RunOptions options;
  bool start_now = false;
};

int run_part(PartArgs& args) {
  install_stop_signals();
  RunOptions& o = args.options;
  o.runtime = Runtime::kReal;
  o.write_lcm_log = false;
  const RigPart part = parse_rig_part(args.part);
  if (part == RigPart::kGround) throw std::invalid_argument("node part: the ground side runs in `a3rig run` itself");
  const Scenario scenario = load_scenario_spec(o.scenario, o.shared_dir);
  const RigConfigs configs = make_rig_configs(scenario, o);
  std::unique_ptr<bridge::CanBus> can;
  VehicleBuses buses;
  if (part == RigPart::kBridge || part == RigPart::kFc) {
    can = bridge::open_can_bus(o.can);
    (part == RigPart::kBridge ? buses.can_bridge : buses.can_fc) = can.get();
  }
  std::unique_ptr<RigThreads> threads;  // outlives the nodes: their destructors cancel timers on it
  RigNodes nodes = make_rig_nodes({part}, configs, o, scenario, {buses}, false);

  int64_t epoch_ns = -1;
  if (!args.start_now) {
    std::printf("ready\n");
    std::fflush(stdout);
    std::string go;
    if (!std::getline(std::cin, go) || go.rfind("go ", 0) != 0) {
      std::fprintf(stderr, "[error] node part %s: expected 'go <epoch ns>' on stdin, got '%s'\n", args.part.c_str(),
                   go.c_str());
      return 1;
    }
    epoch_ns = std::stoll(go.substr(3));
  }
  if (epoch_ns < 0) epoch_ns = common::WallClock::monotonic_now_ns();
  threads = std::make_unique<RigThreads>(nodes, configs, o, o.lcm_url, epoch_ns);
  threads->start();
  int status = 0;
  while (!stop_requested() && status == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (const std::string why = threads->failure(); !why.empty()) {
      std::fprintf(stderr, "[error] node part %s: %s\n", args.part.c_str(), why.c_str());
      status = 1;
    }
  }
  threads->stop_all();
  return status;
}

}  // namespace

A3_REGISTER_COMMAND("90-node-part", [](CLI::App& app) {
  CLI::App* node = app.get_subcommand("node");
  auto args = std::make_shared<PartArgs>();
  CLI::App* cmd = node->add_subcommand(
      "part",
      "Run one part of a rig (dynamics, bridge, fc, linkemu or vehicle: the tool server and airspace monitor) "
      "built from a scenario exactly as `a3rig run` builds it. `a3rig run --processes` starts one per part; it "
      "prints 'ready' when built and starts on 'go <CLOCK_MONOTONIC ns>' from stdin (or at once with --start-now).");
  RunOptions& o = args->options;
  cmd->add_option("name", args->part, "dynamics, bridge, fc, linkemu or vehicle")->required();
  add_run_flag(*cmd, o, RunFlag::kScenario)->required();
  add_run_flag(*cmd, o, RunFlag::kLcmUrl)->required();
  add_run_flags(*cmd, o, {RunFlag::kSeed, RunFlag::kSlice, RunFlag::kRtf, RunFlag::kSync, RunFlag::kCan,
                          RunFlag::kIntegrator, RunFlag::kDynamicsRate, RunFlag::kSharedDir});
  cmd->add_flag("--start-now", args->start_now, "start at once instead of waiting for 'go' on stdin");
  cmd->callback([args] { command_exit_status() = run_part(*args); });
});

}  // namespace a3::rigs
