// Sustained CAN frame rate without loss between two processes on one CanBus transport.
// A child process receives through the bus on a RealTimeExecutor (as a node does) and checks
// every frame's sequence number; the parent sends at each offered rate for a fixed time,
// then with back-pressure as fast as the bus takes frames ("max"). A step passes when every
// frame arrived, in order. Prints one table row per step.
// Usage: bench_can_throughput [--bus SPEC] [--seconds S] [--rates 5000,20000,...,max]
//   SPEC as for open_can_bus: userspace:NAME (default userspace:a3bench), vcan0, ...
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bridge/can/can_bus_factory.hpp"
#include "common/clock.hpp"
#include "common/log.hpp"
#include "common/realtime_executor.hpp"

namespace {

using a3::bridge::CanFrame;

constexpr uint32_t kDataId = 0x10ABCD2A;
constexpr uint32_t kEndId = 0x10ABCE2A;

struct StepResult {
  uint64_t received = 0;
  uint64_t missing = 0;      // sequence numbers skipped
  uint64_t out_of_order = 0;
  uint64_t overruns = 0;     // transport-reported drops
};

CanFrame data_frame(uint64_t seq) {
  CanFrame f;
  f.id = kDataId;
  f.size = 8;
  for (int i = 0; i < 8; ++i) f.data[i] = static_cast<uint8_t>(seq >> (8 * i));
  return f;
}

uint64_t seq_of(const CanFrame& f) {
  uint64_t seq = 0;
  for (int i = 0; i < 8; ++i) seq |= static_cast<uint64_t>(f.data[i]) << (8 * i);
  return seq;
}

int64_t mono_ns() {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1'000'000'000LL + ts.tv_nsec;
}

void sleep_until_ns(int64_t t_ns) {
  struct timespec ts {static_cast<time_t>(t_ns / 1'000'000'000), static_cast<long>(t_ns % 1'000'000'000)};
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

// Child: receive, count, report on the end marker.
[[noreturn]] void receiver(const std::string& spec, int ready_fd, int result_fd) {
  a3::common::set_log_level(a3::common::LogLevel::kWarn);
  a3::common::WallClock clock;
  a3::common::RealTimeExecutor executor(clock);
  auto bus = a3::bridge::open_can_bus(spec);
  StepResult result;
  uint64_t expected = 0;
  std::atomic<bool> reported{false};
  bus->start(executor, [&](const CanFrame& f, int64_t) {
    if (f.id == kDataId) {
      const uint64_t seq = seq_of(f);
      ++result.received;
      if (seq > expected) result.missing += seq - expected;
      if (seq < expected) ++result.out_of_order;
      expected = seq + 1;
    } else if (f.id == kEndId && !reported.exchange(true)) {
      result.overruns = bus->stats().receive_overruns;
      [[maybe_unused]] auto n = ::write(result_fd, &result, sizeof result);
      executor.stop();
    }
  });
  const char ready = 'r';
  [[maybe_unused]] auto n = ::write(ready_fd, &ready, 1);
  executor.run(clock.now_us() + 120'000'000);
  bus->stop();
  ::_exit(reported ? 0 : 1);
}

struct Row {
  std::string offered;
  double achieved_fps = 0;
  uint64_t sent = 0;
  StepResult result;
  bool ok = false;
};

Row run_step(const std::string& spec, double rate_fps, double seconds) {
  int ready_pipe[2], result_pipe[2];
  if (::pipe(ready_pipe) != 0 || ::pipe(result_pipe) != 0) std::exit(2);
  const pid_t child = ::fork();
  if (child == 0) receiver(spec, ready_pipe[1], result_pipe[1]);
  char ready = 0;
  if (::read(ready_pipe[0], &ready, 1) != 1) std::exit(2);
  auto bus = a3::bridge::open_can_bus(spec);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // let the child accept us

  Row row;
  row.offered = rate_fps > 0 ? std::to_string(static_cast<long>(rate_fps)) : "max";
  const int64_t start_ns = mono_ns();
  const int64_t end_ns = start_ns + static_cast<int64_t>(seconds * 1e9);
  uint64_t seq = 0;
  if (rate_fps > 0) {
    const double period_ns = 1e9 / rate_fps;
    const uint64_t total = static_cast<uint64_t>(rate_fps * seconds);
    for (; seq < total; ++seq) {
      const int64_t due = start_ns + static_cast<int64_t>(seq * period_ns);
      if (due > mono_ns() + 200'000) sleep_until_ns(due);
      while (!bus->send(data_frame(seq))) std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
  } else {
    // As fast as the bus takes frames, never more than 256 waiting in the transport.
    while (mono_ns() < end_ns) {
      for (int i = 0; i < 64; ++i) {
        while (bus->tx_pending() > 256 || !bus->send(data_frame(seq))) {
          std::this_thread::sleep_for(std::chrono::microseconds(20));
        }
        ++seq;
      }
    }
  }
  const int64_t sent_ns = mono_ns();
  row.sent = seq;
  // Wait for the transport to drain, then mark the end until the child reports.
  while (bus->tx_pending() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  CanFrame end;
  end.id = kEndId;
  end.size = 0;
  bool got = false;
  for (int attempt = 0; attempt < 3000 && !got; ++attempt) {
    bus->send(end);
    struct pollfd pfd {result_pipe[0], POLLIN, 0};
    if (::poll(&pfd, 1, 10) > 0) {
      got = ::read(result_pipe[0], &row.result, sizeof row.result) == sizeof row.result;
    }
  }
  int status = 0;
  if (!got) ::kill(child, SIGKILL);
  ::waitpid(child, &status, 0);
  row.achieved_fps = static_cast<double>(row.result.received) / ((sent_ns - start_ns) * 1e-9);
  row.ok = got && row.result.received == row.sent && row.result.missing == 0 &&
           row.result.out_of_order == 0;
  for (int fd : {ready_pipe[0], ready_pipe[1], result_pipe[0], result_pipe[1]}) ::close(fd);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::string spec = "userspace:a3bench";
  double seconds = 2.0;
  std::string rates = "5000,10000,20000,50000,100000,max";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    if (key == "--bus") spec = argv[i + 1];
    else if (key == "--seconds") seconds = std::stod(argv[i + 1]);
    else if (key == "--rates") rates = argv[i + 1];
    else {
      std::fprintf(stderr, "bench_can_throughput: unknown option %s\n", key.c_str());
      return 2;
    }
  }
  a3::common::set_log_level(a3::common::LogLevel::kWarn);
  std::printf("CAN transport %s, 8-byte extended frames, sender and receiver in two processes, %.1f s per step\n",
              spec.c_str(), seconds);
  std::printf("%10s %14s %10s %10s %8s %10s %9s  %s\n", "offered/s", "delivered/s", "sent",
              "received", "missing", "reordered", "overruns", "verdict");
  std::stringstream list(rates);
  std::string item;
  double best_ok = 0;
  while (std::getline(list, item, ',')) {
    const double rate = item == "max" ? 0.0 : std::stod(item);
    const Row row = run_step(spec, rate, seconds);
    std::printf("%10s %14.0f %10llu %10llu %8llu %10llu %9llu  %s\n", row.offered.c_str(),
                row.achieved_fps, static_cast<unsigned long long>(row.sent),
                static_cast<unsigned long long>(row.result.received),
                static_cast<unsigned long long>(row.result.missing),
                static_cast<unsigned long long>(row.result.out_of_order),
                static_cast<unsigned long long>(row.result.overruns), row.ok ? "no loss" : "LOSS");
    std::fflush(stdout);
    if (row.ok) best_ok = std::max(best_ok, row.achieved_fps);
  }
  std::printf("sustained without loss: %.0f frames/s (goal >= 5,000)\n", best_ok);
  return 0;
}
