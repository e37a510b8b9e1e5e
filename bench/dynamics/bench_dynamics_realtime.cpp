// Real-time pacing of the dynamics node: the node (RK4 by default) and the patrol flight's
// controller each in their own thread on LCM UDP multicast, paced on the wall clock at a
// real-time factor (1.0 by default), while child processes burn CPU (one by default) on this
// 2-core machine. Prints the lateness of the dynamics steps against their schedule (p50, p99,
// max; from common::RealTimeExecutor), the lateness of the published states as received by
// another thread (step + integration + LCM), and the achieved real-time factor: simulated time
// advanced over wall time, between the first state received after a warm-up second and the
// last one.
#include <CLI/CLI.hpp>

#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bench/dynamics/flight_controller.hpp"
#include "common/runtime.hpp"
#include "dynamics/dynamics_node.hpp"

namespace a3::bench {
namespace {

// Receives every state and notes the monotonic wall time it arrived.
class StateArrivals final : public common::Node {
 public:
  std::string name() const override { return "state_arrivals"; }
  void start(common::Executor&, common::Bus& bus) override {
    bus.subscribe<a3lcm::vehicle_state_t>(common::channels::kState.of(0), [this](const a3lcm::vehicle_state_t& s, int64_t) {
      const int64_t now_ns = common::WallClock::monotonic_now_ns();
      std::lock_guard<std::mutex> lock(mutex_);
      arrivals_.push_back({s.utime_us, now_ns, s.p_W_m[2]});
    });
  }
  struct Arrival {
    int64_t utime_us;
    int64_t mono_ns;
    double z_m;
  };
  std::vector<Arrival> arrivals() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return arrivals_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<Arrival> arrivals_;
};

struct Percentiles {
  double p50 = 0, p99 = 0, max = 0;
  std::size_t count = 0, over_1ms = 0;
};

Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  auto at = [&v](double q) { return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))]; };
  p.p50 = at(0.50);
  p.p99 = at(0.99);
  p.max = v.back();
  p.count = v.size();
  p.over_1ms = static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [](double x) { return x > 1000.0; }));
  return p;
}

pid_t spawn_burner() {
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlive the benchmark
    if (getppid() != parent) _exit(0);
    volatile unsigned long long x = 0;
    while (true) x = x + 1;
  }
  return pid;
}

// Threads of other processes under SCHED_FIFO or SCHED_RR: they preempt every normal thread,
// this benchmark's included, and make its figures say nothing about the dynamics node.
std::string other_realtime_threads() {
  std::set<std::string> names;
  const auto self = std::to_string(getpid());
  std::error_code ec;
  for (const auto& proc : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string pid = proc.path().filename();
    if (pid.empty() || !std::isdigit(static_cast<unsigned char>(pid[0])) || pid == self) continue;
    std::ifstream cmdline(proc.path() / "cmdline");
    if (cmdline.peek() == std::char_traits<char>::eof()) continue;  // a kernel thread
    std::error_code ec2;
    for (const auto& task : std::filesystem::directory_iterator(proc.path() / "task", ec2)) {
      std::ifstream f(task.path() / "stat");
      std::string stat((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
      const auto open = stat.find('('), close = stat.rfind(')');
      if (open == std::string::npos || close == std::string::npos) continue;
      std::istringstream rest(stat.substr(close + 2));
      std::string field;
      // Fields after the name start at 3 (state); the policy is field 41.
      for (int i = 3; i <= 41 && rest >> field; ++i) {
        if (i == 41 && (field == "1" || field == "2")) names.insert(stat.substr(open + 1, close - open - 1) + "[" + pid + "]");
      }
    }
  }
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return a + " " + b + " " + c;
}

struct Options {
  double duration_s = 60.0;
  double rtf = 1.0;
  int burners = 1;
  std::string integrator = "rk4";
  std::string url = "udpm://239.255.76.67:7691?ttl=0";
  std::string dump;
  int rt_priority = 0;
  double warmup_s = 1.0;
};

void add_options(CLI::App& app, Options& o) {
  app.add_option("--duration-s", o.duration_s, "wall seconds measured, after a 1 s warm-up (default 60)")
      ->check(CLI::PositiveNumber);
  app.add_option("--rtf", o.rtf, "real-time factor (default 1)")->check(CLI::PositiveNumber);
  app.add_option("--burners", o.burners, "CPU-burning child processes (default 1)")->check(CLI::Range(0, 16));
  app.add_option("--integrator", o.integrator, "rk4 (default), cvode or ode")
      ->check(CLI::IsMember(dynamics::integrator_names()));
  app.add_option("--lcm-url", o.url, "LCM URL (default: a port of its own, away from other runs)");
  app.add_option("--dump", o.dump, "write each step's lateness (us) and each state's arrival lateness to this CSV");
  app.add_option("--rt-priority", o.rt_priority,
                 "run the node threads under SCHED_FIFO at this priority (1-99; default 0: normal)")
      ->check(CLI::Range(0, 99));
}

// Threads started after this inherit SCHED_FIFO at `priority`; false (and a message) if refused.
bool set_fifo_priority(int priority) {
  sched_param param{};
  param.sched_priority = priority;
  if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0) return true;
  std::fprintf(stderr, "bench_dynamics_realtime: cannot set SCHED_FIFO (needs root or CAP_SYS_NICE)\n");
  return false;
}

void stop_burners(const std::vector<pid_t>& pids) {
  for (pid_t pid : pids) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
}

// Step lateness after the warm-up, over the measured window (the executor keeps them in run order).
std::vector<double> measured_step_lateness(std::vector<double> late_us, const Options& o, double rate_hz) {
  const auto warmup_steps = static_cast<std::size_t>(o.warmup_s * o.rtf * rate_hz);
  const auto window_steps = static_cast<std::size_t>(o.duration_s * o.rtf * rate_hz);
  if (late_us.size() > warmup_steps + window_steps) late_us.resize(warmup_steps + window_steps);
  if (late_us.size() > warmup_steps) late_us.erase(late_us.begin(), late_us.begin() + static_cast<long>(warmup_steps));
  return late_us;
}

// The states received inside the measured window of simulated time.
std::vector<StateArrivals::Arrival> measured_arrivals(const std::vector<StateArrivals::Arrival>& all, const Options& o) {
  std::vector<StateArrivals::Arrival> measured;
  for (const auto& a : all) {
    if (a.utime_us >= static_cast<int64_t>(o.warmup_s * o.rtf * 1e6) &&
        a.utime_us <= static_cast<int64_t>((o.warmup_s + o.duration_s) * o.rtf * 1e6)) {
      measured.push_back(a);
    }
  }
  return measured;
}

void write_dump(const std::string& path, const std::vector<double>& step_late,
                const std::vector<StateArrivals::Arrival>& measured, const common::WallClock& clock) {
  std::ofstream out(path);
  out << "kind,index_or_utime_us,lateness_us\n";
  for (std::size_t i = 0; i < step_late.size(); ++i) out << "step," << i << ',' << step_late[i] << '\n';
  for (const auto& a : measured) out << "state," << a.utime_us << ',' << (a.mono_ns - clock.mono_ns_at(a.utime_us)) * 1e-3 << '\n';
}

// What the run saw, for the report.
struct Run {
  std::string load_before, load_after, realtime_before, realtime_after;
  Percentiles steps, states;
  double achieved = 0.0, wall_s = 0.0, expected_states = 0.0, rate_hz = 0.0, final_z_m = 0.0;
  std::string counters;
};

void print_report(const Options& o, const Run& r) {
  std::printf("dynamics node in real time: %s integrator, %.0f Hz, real-time factor %g, patrol flight under its\n"
              "controller (own thread), LCM %s; %d CPU-burning child process(es); %.0f s measured after %.0f s\n"
              "warm-up; load average before %s, after %s; %u cores; node threads %s\n",
              o.integrator.c_str(), r.rate_hz, o.rtf, o.url.c_str(), o.burners, o.duration_s, o.warmup_s,
              r.load_before.c_str(), r.load_after.c_str(), std::thread::hardware_concurrency(),
              o.rt_priority > 0 ? ("SCHED_FIFO " + std::to_string(o.rt_priority)).c_str() : "SCHED_OTHER");
  std::printf("other processes' SCHED_FIFO/RR threads (they preempt this run): before %s; after %s\n",
              r.realtime_before.c_str(), r.realtime_after.c_str());
  std::printf("%-36s %9s %9s %9s %8s %9s\n", "lateness against the schedule", "p50 us", "p99 us", "max us", "n", "> 1 ms");
  std::printf("%-36s %9.0f %9.0f %9.0f %8zu %9zu\n", "dynamics step start (executor)", r.steps.p50, r.steps.p99,
              r.steps.max, r.steps.count, r.steps.over_1ms);
  std::printf("%-36s %9.0f %9.0f %9.0f %8zu %9zu\n", "state received by another thread", r.states.p50, r.states.p99,
              r.states.max, r.states.count, r.states.over_1ms);
  std::printf("achieved real-time factor: %.5f (%.3f simulated s in %.3f wall s; %zu of %.0f states received)\n",
              r.achieved, r.achieved * r.wall_s, r.wall_s, r.states.count, r.expected_states);
  std::printf("node counters: %s; final z %.1f m\n", r.counters.c_str(), r.final_z_m);
}

}  // namespace
}  // namespace a3::bench

int main(int argc, char** argv) {
  using namespace a3;
  using namespace a3::bench;
  CLI::App app("Real-time jitter and achieved real-time factor of the dynamics node under CPU load.");
  Options o;
  add_options(app, o);
  CLI11_PARSE(app, argc, argv);

  const double sim_end_s = (o.duration_s + o.warmup_s + 0.5) * o.rtf;
  dynamics::DynamicsNodeConfig config;
  config.integrator = dynamics::parse_integrator_kind(o.integrator);
  const common::WallClock clock(o.rtf);
  dynamics::DynamicsNode dyn(config);
  FlightControllerNode controller(config.params, patrol_plan(sim_end_s + 1.0));
  StateArrivals arrivals;
  common::RealTimeNodeThread arrivals_thread(arrivals, clock, o.url);
  arrivals_thread.bus().check_loopback();
  common::RealTimeNodeThread dyn_thread(dyn, clock, o.url);
  common::RealTimeNodeThread controller_thread(controller, clock, o.url);

  std::vector<pid_t> burner_pids;
  for (int i = 0; i < o.burners; ++i) burner_pids.push_back(spawn_burner());
  if (o.rt_priority > 0 && !set_fifo_priority(o.rt_priority)) {  // the burners keep the normal policy
    stop_burners(burner_pids);
    return 1;
  }
  Run r;
  r.load_before = load_average();
  r.realtime_before = other_realtime_threads();
  arrivals_thread.start();
  dyn_thread.start();
  controller_thread.start();
  std::this_thread::sleep_for(std::chrono::duration<double>(o.duration_s + o.warmup_s + 0.5));
  controller_thread.stop_and_join();
  dyn_thread.stop_and_join();
  arrivals_thread.stop_and_join();
  stop_burners(burner_pids);
  r.load_after = load_average();
  r.realtime_after = other_realtime_threads();

  r.rate_hz = config.publish_rate_hz;
  const std::vector<double> step_late =
      measured_step_lateness(dyn_thread.executor().lateness_samples_us(), o, config.publish_rate_hz);
  r.steps = percentiles(step_late);
  const auto all = arrivals.arrivals();
  const std::vector<StateArrivals::Arrival> measured = measured_arrivals(all, o);
  std::vector<double> state_late;
  for (const auto& a : measured) state_late.push_back((a.mono_ns - clock.mono_ns_at(a.utime_us)) * 1e-3);
  r.states = percentiles(state_late);
  if (measured.size() >= 2) {
    r.wall_s = (measured.back().mono_ns - measured.front().mono_ns) * 1e-9;
    r.achieved = (measured.back().utime_us - measured.front().utime_us) * 1e-6 / r.wall_s;
  }
  if (!o.dump.empty()) write_dump(o.dump, step_late, measured, clock);
  r.expected_states = o.duration_s * o.rtf * config.publish_rate_hz + 1;
  r.counters = common::to_text(dyn.counters());
  r.final_z_m = all.empty() ? 0.0 : all.back().z_m;
  print_report(o, r);
  return 0;
}
