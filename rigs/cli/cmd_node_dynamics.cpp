// `a3rig node dynamics`: the vehicle dynamics as its own real-time process on LCM. It listens
// for rotor commands on A3_ACTUATORS and publishes the vehicle state on A3_STATE, paced on the
// wall clock scaled by the real-time factor, and reports the achieved real-time factor.
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "common/json_file.hpp"
#include "common/runtime.hpp"
#include "dynamics/actuator_script_node.hpp"
#include "dynamics/dynamics_node.hpp"
#include "dynamics/scenario_setup.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/node_thread_loop.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/scenario/initial_state.hpp"

namespace a3::rigs {
namespace {

struct DynamicsArgs {
  std::string airframe;
  std::string scenario;
  bool on_ground = false;
  std::string integrator = "rk4";
  double rate_hz = 100.0;
  double command_timeout_s = 0.5;
  double wind_mps = -1.0;
  double wind_dir_deg = 0.0;
  bool no_turbulence = false;
  uint64_t seed = 1;
  std::string lcm_url;
  std::string demo;
  NodePacing pacing;
};

int run_dynamics(const DynamicsArgs& args) {
  dynamics::DynamicsNodeConfig config;
  if (!args.airframe.empty()) config.params = dynamics::airframe_by_name_or_path(args.airframe);
  config.integrator = dynamics::parse_integrator_kind(args.integrator);
  config.publish_rate_hz = args.rate_hz;
  config.command_timeout_s = args.command_timeout_s;
  config.seed = args.seed;
  config.turbulence.enabled = !args.no_turbulence;
  if (!args.scenario.empty()) {
    dynamics::apply_flight_start(flight_start(load_initial_state_file(args.scenario)), args.on_ground, config);
  }
  if (args.wind_mps >= 0.0) config.mean_wind_W_mps = dynamics::wind_from_report(args.wind_mps, args.wind_dir_deg);

  const common::WallClock clock(args.pacing.rtf);
  dynamics::DynamicsNode node(config);
  common::RealTimeNodeThread thread(node, clock, args.lcm_url);
  thread.bus().check_loopback();
  std::unique_ptr<dynamics::ActuatorScriptNode> demo;
  std::unique_ptr<common::RealTimeNodeThread> demo_thread;
  if (!args.demo.empty()) {
    const double hover = node.model().hover_throttle();
    demo = std::make_unique<dynamics::ActuatorScriptNode>(
        dynamics::ActuatorScriptNode::ThrottleFn{[hover, kind = args.demo](double t) {
          // hover: hold; climb: 3 s up at 10 % more thrust per rotor, then hold.
          const double scale = kind == "climb" && t > 1.0 && t < 4.0 ? 1.1 : 1.0;
          return std::array<double, 4>{hover * scale, hover * scale, hover * scale, hover * scale};
        }});
    demo_thread = std::make_unique<common::RealTimeNodeThread>(*demo, clock, args.lcm_url);
  }
  std::fprintf(stderr,
               "a3rig node dynamics: %s, %s integrator, %.0f Hz on %s, real-time factor %g, LCM %s\n",
               config.params.name.c_str(), args.integrator.c_str(), args.rate_hz, "A3_STATE", args.pacing.rtf,
               thread.bus().url().c_str());
  install_stop_signals();
  thread.start();
  if (demo_thread) demo_thread->start();

  const int64_t wall0_ns = common::WallClock::monotonic_now_ns();
  uint64_t steps0 = 0;
  int64_t wall_prev_ns = wall0_ns;
  while (!stop_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const double sim_s = clock.now_s();
    if (!thread.failure().empty()) break;
    const int64_t wall_ns = common::WallClock::monotonic_now_ns();
    if ((wall_ns - wall_prev_ns) * 1e-9 >= args.pacing.report_every_s || (args.pacing.duration_s > 0 && sim_s >= args.pacing.duration_s)) {
      const uint64_t steps = node.counters().get("steps");
      const double window_sim_s = (steps - steps0) / args.rate_hz;
      const double window_wall_s = (wall_ns - wall_prev_ns) * 1e-9;
      const auto& s = node.integrator().state();
      std::fprintf(stderr, "t=%8.1f s  achieved real-time factor %.4f  z=%.2f m  %s\n", sim_s,
                   window_sim_s / window_wall_s, s.p_W_m.z(), common::to_text(node.counters()).c_str());
      steps0 = steps;
      wall_prev_ns = wall_ns;
    }
    if (args.pacing.duration_s > 0 && sim_s >= args.pacing.duration_s) break;
  }
  if (demo_thread) demo_thread->stop_and_join();
  thread.stop_and_join();
  if (!thread.failure().empty()) {
    std::cerr << "a3rig node dynamics: stopped by an error: " << thread.failure() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("50-node-dynamics", [](CLI::App& app) {
  auto args = std::make_shared<DynamicsArgs>();
  CLI::App* node = app.get_subcommand("node");
  CLI::App* cmd = node->add_subcommand(
      "dynamics",
      "Run the vehicle dynamics in real time on LCM: rotor commands in (A3_ACTUATORS, "
      "actuator_cmd_t), vehicle state out (A3_STATE, vehicle_state_t), crashes on A3_SAFETY. "
      "Stops on Ctrl-C or after --duration-s.");
  cmd->add_option("--airframe", args->airframe,
                  "built-in airframe (iris, the default, or heavy-lift) or an airframe JSON file");
  cmd->add_option("--scenario", args->scenario,
                  "α³-Bench episode or initial_state JSON: wind, payloads and start pose")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--on-ground", args->on_ground, "start on the ground below the scenario's pose");
  cmd->add_option("--integrator", args->integrator, "rk4 (default: fixed-step Runge-Kutta), cvode (adaptive, the accuracy reference) or ode")
      ->check(CLI::IsMember(dynamics::integrator_names()));
  cmd->add_option("--rate-hz", args->rate_hz, "state publish rate (default 100)")->check(a3::rigs::between(1.0, 10000.0));
  cmd->add_option("--command-timeout-s", args->command_timeout_s,
                  "spin the motors down after this long without a command (default 0.5)")
      ->check(a3::rigs::positive());
  cmd->add_option("--wind-mps", args->wind_mps, "mean wind speed (overrides the scenario)")->check(a3::rigs::non_negative());
  cmd->add_option("--wind-dir-deg", args->wind_dir_deg, "direction the wind blows from, degrees from north");
  cmd->add_flag("--no-turbulence", args->no_turbulence, "mean wind only");
  cmd->add_option("--seed", args->seed, "seed of the turbulence (default 1)");
  cmd->add_option("--demo", args->demo, "also publish rotor commands: hover or climb (for a quick look)")
      ->check(CLI::IsMember({"hover", "climb"}));
  add_lcm_url_flag(*cmd, args->lcm_url);
  add_node_pacing_flags(*cmd, args->pacing);
  cmd->callback([args] { command_exit_status() = run_dynamics(*args); });
});

}  // namespace a3::rigs
