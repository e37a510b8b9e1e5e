// Virtual-time speed of the dynamics node: the patrol flight (flight_controller.hpp: take-off,
// then legs, turns and climbs repeated every 40 s) flown by a controller node publishing rotor
// commands at 100 Hz, the dynamics node publishing A3_STATE at 100 Hz, both on
// common::VirtualRuntime (one thread, LCM-encoded bytes on the in-process bus). Prints simulated
// seconds per wall second for fixed-step RK4 (the default), CVODE and ODE, calm and in turbulent
// wind, the solver statistics per simulated second, and the same integrators stepped directly
// with the same controller (no node, no bus) to show what the bus and the nodes cost; SUNDIALS
// ARKODE's ERKStep with the same RK4 table and steps is measured alone (arkode_erk_integrator.hpp),
// the library alternative to the hand-written RK4. The last variants hold a constant hover
// command from an ActuatorScriptNode: CVODE's best case, no restarts. With --csv it also writes
// the first variant's flight (commands and states as they went over the bus) for the SciPy
// comparison (scipy_model.py).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "bench/dynamics/arkode_erk_integrator.hpp"
#include "bench/dynamics/bus_recorder.hpp"
#include "bench/dynamics/flight_controller.hpp"
#include "common/runtime.hpp"
#include "dynamics/actuator_script_node.hpp"
#include "dynamics/cvode_integrator.hpp"
#include "dynamics/dynamics_node.hpp"
#include "dynamics/rk4_integrator.hpp"

namespace a3::bench {
namespace {

struct Variant {
  std::string name;
  dynamics::IntegratorKind kind;
  bool turbulence;
  bool hover_script = false;  // constant hover command from an ActuatorScriptNode, airborne
  bool arkode_erk = false;    // ARKODE ERKStep instead of `kind`, measured alone only
};

// Steps and right-hand-side evaluations of the solver, for the statistics columns.
struct SolverStats {
  long steps = 0, rhs_evaluations = 0, error_test_failures = 0, convergence_failures = 0, restarts = 0;
  bool known = false;
};

SolverStats stats_of(const dynamics::Integrator& integrator) {
  SolverStats out;
  if (const auto* cv = dynamic_cast<const dynamics::CvodeIntegrator*>(&integrator)) {
    const auto s = cv->stats();
    out = {s.steps, s.rhs_evaluations, s.error_test_failures, s.convergence_failures, s.restarts, true};
  } else if (const auto* rk = dynamic_cast<const dynamics::Rk4Integrator*>(&integrator)) {
    out = {rk->stats().steps, rk->stats().rhs_evaluations, 0, 0, 0, true};
  } else if (const auto* erk = dynamic_cast<const ArkodeErkIntegrator*>(&integrator)) {
    out = {erk->steps(), 4 * erk->steps(), 0, 0, 0, true};
  }
  return out;
}

struct Result {
  double wall_s = 0.0;
  double cpu_s = 0.0;  // of this process: what the run costs without other load on the machine
  a3lcm::vehicle_state_t last{};
  SolverStats stats;
  uint64_t states = 0;
};

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double cpu_now_s() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

dynamics::DynamicsNodeConfig config_for(const Variant& v, double rtol) {
  dynamics::DynamicsNodeConfig config;
  const dynamics::QuadrotorModel model(config.params);
  config.integrator = v.kind;
  config.integrator_options.relative_tolerance = rtol;
  if (v.hover_script) {
    config.initial_state.p_W_m = {0, 0, 30};
    config.initial_state.rotor_speed_radps.fill(model.hover_speed_radps());
  }  // else on the ground, rotors stopped
  config.turbulence.enabled = v.turbulence;
  // A fresh breeze with Dryden turbulence (σ ≈ 1.1 m/s horizontal at 50 m).
  if (v.turbulence) config.mean_wind_W_mps = dynamics::wind_from_report(8.0, 240.0);
  config.seed = 42;
  return config;
}

// The dynamics node and the controller (or script) node on the virtual runtime, for sim_s
// simulated seconds. Each message has one subscriber, its consumer, as in an episode without
// a logger: the controller takes A3_STATE (and reports the last state it heard), the dynamics
// A3_ACTUATORS; with the script node, which does not listen, a recorder takes A3_STATE. `keep`
// (the CSV) adds a recorder of every message.
Result run_node(const Variant& v, double sim_s, double rtol, BusRecorder* keep) {
  const dynamics::DynamicsNodeConfig config = config_for(v, rtol);
  const dynamics::QuadrotorModel model(config.params);
  common::VirtualRuntime rt;
  dynamics::DynamicsNode dyn(config);
  const double hover = model.hover_throttle();
  dynamics::ActuatorScriptNode script(dynamics::ActuatorScriptNode::ThrottleFn{
      [hover](double) { return std::array<double, 4>{hover, hover, hover, hover}; }});
  FlightControllerNode controller(config.params, patrol_plan(sim_s));
  BusRecorder last_only(false);
  if (keep != nullptr) rt.add(*keep);
  if (v.hover_script && keep == nullptr) rt.add(last_only);
  rt.add(dyn);
  if (v.hover_script) {
    rt.add(script);
  } else {
    rt.add(controller);
  }
  const double t0 = now_s(), c0 = cpu_now_s();
  rt.run_until(static_cast<int64_t>(sim_s * 1e6));
  Result r;
  r.wall_s = now_s() - t0;
  r.cpu_s = cpu_now_s() - c0;
  if (keep != nullptr || v.hover_script) {
    const BusRecorder& recorder = keep != nullptr ? *keep : last_only;
    r.last = recorder.last_state();
    r.states = recorder.state_count();
  } else {
    r.last = controller.last_state();
    r.states = controller.states_received();
  }
  r.stats = stats_of(dyn.integrator());
  return r;
}

// The integrator alone, stepped on the same 10 ms grid with the same controller.
Result run_integrator(const Variant& v, double sim_s, double rtol) {
  const dynamics::DynamicsNodeConfig config = config_for(v, rtol);
  const dynamics::QuadrotorModel model(config.params);
  dynamics::WindField wind(config.mean_wind_W_mps, config.turbulence, config.seed);
  std::unique_ptr<dynamics::Integrator> integrator =
      v.arkode_erk ? std::make_unique<ArkodeErkIntegrator>(model, wind)
                   : dynamics::make_integrator(v.kind, model, wind, config.integrator_options);
  integrator->reset(config.initial_state, 0.0);
  FlightController controller(config.params, patrol_plan(sim_s));
  const double hover = model.hover_throttle();
  const int steps = static_cast<int>(std::lround(sim_s * 100));
  const double t0 = now_s(), c0 = cpu_now_s();
  for (int k = 0; k < steps; ++k) {
    const auto throttle =
        v.hover_script ? std::array<double, 4>{hover, hover, hover, hover}
                       : controller.throttle(k * 0.01 + 0.005, input_of(integrator->state(), integrator->on_ground()));
    dynamics::RotorSpeeds command;
    for (int i = 0; i < 4; ++i) command[i] = model.throttle_to_speed_radps(throttle[i]);
    integrator->advance_to((k + 1) * 0.01, command);
  }
  Result r;
  r.wall_s = now_s() - t0;
  r.cpu_s = cpu_now_s() - c0;
  r.stats = stats_of(*integrator);
  for (int i = 0; i < 3; ++i) r.last.p_W_m[i] = integrator->state().p_W_m[i];
  return r;
}

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

template <typename Fn>
Result median_of(int repeats, Fn run) {
  std::vector<Result> results;
  for (int i = 0; i < repeats; ++i) results.push_back(run());
  std::sort(results.begin(), results.end(), [](const Result& a, const Result& b) { return a.wall_s < b.wall_s; });
  return results[results.size() / 2];
}

void write_csv(const std::string& path, const BusRecorder& rec, const dynamics::QuadrotorModel& model) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << std::setprecision(17);
  // Row k: the state published at t_k and the rotor speed command (rad/s) the node applied over
  // [t_k, t_k+1] (published at t_k + 5 ms); the last row has no command.
  out << "t_s,cmd0,cmd1,cmd2,cmd3,px,py,pz,vx,vy,vz,qw,qx,qy,qz,wx,wy,wz,r0,r1,r2,r3,battery_pct\n";
  const auto& states = rec.states();
  const auto& commands = rec.commands();
  for (std::size_t k = 0; k < states.size(); ++k) {
    const auto& s = states[k];
    out << s.utime_us * 1e-6;
    for (int i = 0; i < 4; ++i) {
      out << ',';
      if (k < commands.size()) out << model.throttle_to_speed_radps(commands[k].throttle[i]);
    }
    for (double x : s.p_W_m) out << ',' << x;
    for (double x : s.v_W_mps) out << ',' << x;
    for (double x : s.q_WB) out << ',' << x;
    for (double x : s.w_B_radps) out << ',' << x;
    for (double x : s.rotor_speed_radps) out << ',' << x;
    out << ',' << s.battery_pct << '\n';
  }
}

}  // namespace
}  // namespace a3::bench

int main(int argc, char** argv) {
  using namespace a3;
  using namespace a3::bench;
  CLI::App app("Virtual-time speed of the dynamics node (simulated seconds per wall second).");
  double sim_s = 600.0;
  int repeats = 3;
  double rtol = dynamics::IntegratorOptions{}.relative_tolerance;
  std::string only;
  std::string csv;
  double csv_s = 60.0;
  int digits = 4;
  app.add_option("--sim-s", sim_s, "simulated seconds per run (default 600)")->check(CLI::PositiveNumber);
  app.add_option("--repeats", repeats, "runs per variant; the median is printed (default 3)")->check(CLI::Range(1, 100));
  app.add_option("--rtol", rtol, "CVODE relative tolerance (default: the node's)")->check(CLI::PositiveNumber);
  app.add_option("--only", only, "run only the variants whose name contains this");
  app.add_option("--csv", csv,
                 "also write the flight of the first variant run (bus commands and states) to this CSV");
  app.add_option("--csv-s", csv_s, "simulated seconds in the CSV (default 60)")->check(CLI::PositiveNumber);
  app.add_option("--digits", digits, "decimals of the final positions (default 4; 17 to compare builds bit for bit)")
      ->check(CLI::Range(0, 17));
  CLI11_PARSE(app, argc, argv);

  const std::vector<Variant> variants = {
      {"rk4 calm", dynamics::IntegratorKind::kRk4, false},
      {"rk4 turbulence", dynamics::IntegratorKind::kRk4, true},
      {"arkode-erk rk4 calm", dynamics::IntegratorKind::kRk4, false, false, true},
      {"arkode-erk rk4 turbulence", dynamics::IntegratorKind::kRk4, true, false, true},
      {"cvode calm", dynamics::IntegratorKind::kCvode, false},
      {"cvode turbulence", dynamics::IntegratorKind::kCvode, true},
      {"ode calm", dynamics::IntegratorKind::kOde, false},
      {"ode turbulence", dynamics::IntegratorKind::kOde, true},
      {"rk4 hover, constant cmd", dynamics::IntegratorKind::kRk4, false, true},
      {"cvode hover, constant cmd", dynamics::IntegratorKind::kCvode, false, true},
      {"ode hover, constant cmd", dynamics::IntegratorKind::kOde, false, true},
  };

  std::printf("dynamics node in virtual time: closed-loop patrol flight (take-off, 40 s cycle of legs, turns,\n"
              "climbs), rotor commands and A3_STATE at 100 Hz through the virtual bus; %.0f simulated s per run,\n"
              "median of %d; RK4 step %.1f ms (ARKODE ERKStep the same), CVODE rtol %g, ODE step 0.5 ms\n", sim_s, repeats,
              1e3 * dynamics::default_rk4_step_s(dynamics::default_vehicle_params()), rtol);
  std::printf("turbulence: mean wind 8 m/s from 240 deg, Dryden; hover: constant command from a script node\n");
  std::printf("node: controller + dynamics nodes on the virtual runtime, simulated s per wall s (and per CPU s\n"
              "of this process: the figure without other load); alone: controller and integrator stepped\n"
              "directly, no bus; load average %s\n", load_average().c_str());
  std::printf(
              "per simulated second: steps, RHS evaluations; CVODE also error-test failures, nonlinear\n"
              "convergence failures, restarts (CVodeReInit: command changes, contact, renormalisation)\n\n");
  std::printf("%-27s %10s %10s %10s | %8s %8s %8s %8s %8s | %s\n", "variant", "node xRT", "(CPU)", "alone xRT",
              "steps/s", "RHS/s", "etf/s", "ncf/s", "restart/s", "final position (m)");
  const Variant* first = nullptr;
  for (const Variant& v : variants) {
    if (!only.empty() && v.name.find(only) == std::string::npos) continue;
    if (first == nullptr) first = &v;
    const Result node = v.arkode_erk ? Result{} : median_of(repeats, [&] { return run_node(v, sim_s, rtol, nullptr); });
    const Result alone = median_of(repeats, [&] { return run_integrator(v, sim_s, rtol); });
    const auto expected_states = static_cast<uint64_t>(std::llround(sim_s * 100)) + 1;
    if (!v.arkode_erk && node.states != expected_states) {
      std::fprintf(stderr, "%s: %llu states published, expected %llu\n", v.name.c_str(),
                   static_cast<unsigned long long>(node.states), static_cast<unsigned long long>(expected_states));
      return 1;
    }
    if (v.arkode_erk) {
      std::printf("%-27s %10s %10s %9.0fx |", v.name.c_str(), "-", "-", sim_s / alone.wall_s);
    } else {
      std::printf("%-27s %9.0fx %9.0fx %9.0fx |", v.name.c_str(), sim_s / node.wall_s, sim_s / node.cpu_s,
                  sim_s / alone.wall_s);
    }
    const SolverStats& s = v.arkode_erk ? alone.stats : node.stats;
    if (v.kind == dynamics::IntegratorKind::kCvode) {
      std::printf(" %8.0f %8.0f %8.1f %8.1f %9.1f |", s.steps / sim_s, s.rhs_evaluations / sim_s,
                  s.error_test_failures / sim_s, s.convergence_failures / sim_s, s.restarts / sim_s);
    } else if (s.known) {
      std::printf(" %8.0f %8.0f %8s %8s %9s |", s.steps / sim_s, s.rhs_evaluations / sim_s, "-", "-", "-");
    } else {
      std::printf(" %8s %8s %8s %8s %9s |", "-", "-", "-", "-", "-");
    }
    // ARKODE runs alone only: its final position is the alone run's, comparable with RK4's node run (same steps).
    const a3lcm::vehicle_state_t& last = v.arkode_erk ? alone.last : node.last;
    std::printf(" (%.*f, %.*f, %.*f)\n", digits, last.p_W_m[0], digits, last.p_W_m[1], digits, last.p_W_m[2]);
    std::fflush(stdout);
  }

  if (!csv.empty() && first != nullptr) {
    BusRecorder rec(true);
    run_node(*first, csv_s, rtol, &rec);
    write_csv(csv, rec, dynamics::QuadrotorModel(dynamics::default_vehicle_params()));
    std::printf("\nwrote %s (%.0f s of the %s flight)\n", csv.c_str(), csv_s, first->name.c_str());
  }
  return 0;
}
