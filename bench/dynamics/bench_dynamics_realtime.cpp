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

}  // namespace
}  // namespace a3::bench

int main(int argc, char** argv) {
  using namespace a3;
  using namespace a3::bench;
  CLI::App app("Real-time jitter and achieved real-time factor of the dynamics node under CPU load.");
  double duration_s = 60.0;
  double rtf = 1.0;
  int burners = 1;
  std::string integrator = "rk4";
  std::string url = "udpm://239.255.76.67:7691?ttl=0";
  std::string dump;
  int rt_priority = 0;
  app.add_option("--duration-s", duration_s, "wall seconds measured, after a 1 s warm-up (default 60)")
      ->check(CLI::PositiveNumber);
  app.add_option("--rtf", rtf, "real-time factor (default 1)")->check(CLI::PositiveNumber);
  app.add_option("--burners", burners, "CPU-burning child processes (default 1)")->check(CLI::Range(0, 16));
  app.add_option("--integrator", integrator, "rk4 (default), cvode or ode")->check(CLI::IsMember(dynamics::integrator_names()));
  app.add_option("--lcm-url", url, "LCM URL (default: a port of its own, away from other runs)");
  app.add_option("--dump", dump, "write each step's lateness (us) and each state's arrival lateness to this CSV");
  app.add_option("--rt-priority", rt_priority,
                 "run the node threads under SCHED_FIFO at this priority (1-99; default 0: normal)")
      ->check(CLI::Range(0, 99));
  CLI11_PARSE(app, argc, argv);

  const double warmup_s = 1.0;
  const double sim_end_s = (duration_s + warmup_s + 0.5) * rtf;
  dynamics::DynamicsNodeConfig config;
  config.integrator = dynamics::parse_integrator_kind(integrator);
  const common::WallClock clock(rtf);
  dynamics::DynamicsNode dyn(config);
  FlightControllerNode controller(config.params, patrol_plan(sim_end_s + 1.0));
  StateArrivals arrivals;
  common::RealTimeNodeThread arrivals_thread(arrivals, clock, url);
  arrivals_thread.bus().check_loopback();
  common::RealTimeNodeThread dyn_thread(dyn, clock, url);
  common::RealTimeNodeThread controller_thread(controller, clock, url);

  std::vector<pid_t> burner_pids;
  for (int i = 0; i < burners; ++i) burner_pids.push_back(spawn_burner());
  if (rt_priority > 0) {
    // Threads started from here on inherit the policy; the burners keep the normal one.
    sched_param param{};
    param.sched_priority = rt_priority;
    if (pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) != 0) {
      std::fprintf(stderr, "bench_dynamics_realtime: cannot set SCHED_FIFO (needs root or CAP_SYS_NICE)\n");
      for (pid_t pid : burner_pids) kill(pid, SIGKILL);
      return 1;
    }
  }
  const std::string load_before = load_average();
  const std::string realtime_before = other_realtime_threads();
  arrivals_thread.start();
  dyn_thread.start();
  controller_thread.start();
  std::this_thread::sleep_for(std::chrono::duration<double>(duration_s + warmup_s + 0.5));
  controller_thread.stop_and_join();
  dyn_thread.stop_and_join();
  arrivals_thread.stop_and_join();
  for (pid_t pid : burner_pids) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
  }
  const std::string load_after = load_average();
  const std::string realtime_after = other_realtime_threads();

  // Step lateness after the warm-up (the executor keeps them in run order).
  std::vector<double> step_late = dyn_thread.executor().lateness_samples_us();
  const auto warmup_steps = static_cast<std::size_t>(warmup_s * rtf * config.publish_rate_hz);
  const auto window_steps = static_cast<std::size_t>(duration_s * rtf * config.publish_rate_hz);
  if (step_late.size() > warmup_steps + window_steps) step_late.resize(warmup_steps + window_steps);
  if (step_late.size() > warmup_steps) step_late.erase(step_late.begin(), step_late.begin() + static_cast<long>(warmup_steps));
  const Percentiles steps = percentiles(step_late);

  const auto all = arrivals.arrivals();
  std::vector<StateArrivals::Arrival> measured;
  for (const auto& a : all) {
    if (a.utime_us >= static_cast<int64_t>(warmup_s * rtf * 1e6) &&
        a.utime_us <= static_cast<int64_t>((warmup_s + duration_s) * rtf * 1e6)) {
      measured.push_back(a);
    }
  }
  std::vector<double> state_late;
  for (const auto& a : measured) state_late.push_back((a.mono_ns - clock.mono_ns_at(a.utime_us)) * 1e-3);
  const Percentiles states = percentiles(state_late);
  double achieved = 0.0, wall_s = 0.0;
  if (measured.size() >= 2) {
    wall_s = (measured.back().mono_ns - measured.front().mono_ns) * 1e-9;
    achieved = (measured.back().utime_us - measured.front().utime_us) * 1e-6 / wall_s;
  }
  if (!dump.empty()) {
    std::ofstream out(dump);
    out << "kind,index_or_utime_us,lateness_us\n";
    for (std::size_t i = 0; i < step_late.size(); ++i) out << "step," << i << ',' << step_late[i] << '\n';
    for (const auto& a : measured) out << "state," << a.utime_us << ',' << (a.mono_ns - clock.mono_ns_at(a.utime_us)) * 1e-3 << '\n';
  }
  const double expected_states = duration_s * rtf * config.publish_rate_hz + 1;

  std::printf("dynamics node in real time: %s integrator, %.0f Hz, real-time factor %g, patrol flight under its\n"
              "controller (own thread), LCM %s; %d CPU-burning child process(es); %.0f s measured after %.0f s\n"
              "warm-up; load average before %s, after %s; %u cores; node threads %s\n",
              integrator.c_str(), config.publish_rate_hz, rtf, url.c_str(), burners, duration_s, warmup_s,
              load_before.c_str(), load_after.c_str(), std::thread::hardware_concurrency(),
              rt_priority > 0 ? ("SCHED_FIFO " + std::to_string(rt_priority)).c_str() : "SCHED_OTHER");
  std::printf("other processes' SCHED_FIFO/RR threads (they preempt this run): before %s; after %s\n",
              realtime_before.c_str(), realtime_after.c_str());
  std::printf("%-36s %9s %9s %9s %8s %9s\n", "lateness against the schedule", "p50 us", "p99 us", "max us", "n", "> 1 ms");
  std::printf("%-36s %9.0f %9.0f %9.0f %8zu %9zu\n", "dynamics step start (executor)", steps.p50, steps.p99, steps.max,
              steps.count, steps.over_1ms);
  std::printf("%-36s %9.0f %9.0f %9.0f %8zu %9zu\n", "state received by another thread", states.p50, states.p99,
              states.max, states.count, states.over_1ms);
  std::printf("achieved real-time factor: %.5f (%.3f simulated s in %.3f wall s; %zu of %.0f states received)\n",
              achieved, achieved * wall_s, wall_s, states.count, expected_states);
  std::printf("node counters: %s; final z %.1f m\n", common::to_text(dyn.counters()).c_str(),
              all.empty() ? 0.0 : all.back().z_m);
  return 0;
}
