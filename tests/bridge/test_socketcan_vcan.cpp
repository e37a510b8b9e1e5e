// SocketCAN on a real vcan0 (run through scripts/vcan-vm/with-vcan.sh, CTest label "vcan"):
// frames sent through SocketCanBus reach another socket and candump, frames from cansend
// reach the bus, and multi-frame DroneCAN transfers survive the kernel's CAN stack. Without
// vcan0 the tests skip, unless A3_REQUIRE_VCAN=1 (set by the CTest entry) makes that a failure.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/can/socketcan_bus.hpp"
#include "bridge/dronecan/json_codec.hpp"
#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/node.hpp"
#include "common/clock.hpp"
#include "common/realtime_executor.hpp"

namespace a3::bridge {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

#define A3_REQUIRE_VCAN0()                                                                   \
  if (const std::string why = SocketCanBus::probe("vcan0"); !why.empty()) {                 \
    const char* require = std::getenv("A3_REQUIRE_VCAN");                                   \
    if (require != nullptr && std::string(require) == "1") FAIL() << "vcan0: " << why;     \
    GTEST_SKIP() << "needs a SocketCAN vcan0 (" << why                                       \
                 << "); run it through scripts/vcan-vm/with-vcan.sh";                        \
  }

class ExecutorThread {
 public:
  ExecutorThread() : executor_(clock_), thread_([this] { executor_.run(); }) {}
  ~ExecutorThread() {
    executor_.stop();
    thread_.join();
  }
  common::RealTimeExecutor& executor() { return executor_; }

 private:
  common::WallClock clock_;
  common::RealTimeExecutor executor_;
  std::thread thread_;
};

class Inbox {
 public:
  CanFrameHandler handler() {
    return [this](const CanFrame& f, int64_t) {
      std::lock_guard lock(mutex_);
      frames_.push_back(f);
    };
  }
  std::vector<CanFrame> wait_for(std::size_t n, std::chrono::milliseconds limit) {
    const auto deadline = Clock::now() + limit;
    while (Clock::now() < deadline) {
      {
        std::lock_guard lock(mutex_);
        if (frames_.size() >= n) break;
      }
      std::this_thread::sleep_for(2ms);
    }
    std::lock_guard lock(mutex_);
    return frames_;
  }

 private:
  std::mutex mutex_;
  std::vector<CanFrame> frames_;
};

// candump -L on vcan0 as a child process whose lines we read from a pipe.
class Candump {
 public:
  Candump() {
    int fds[2];
    if (::pipe(fds) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(fds[1], STDOUT_FILENO);
      ::close(fds[0]);
      ::close(fds[1]);
      // A large receive buffer: candump's default (~300 frames) overflows in bursts when it
      // runs slowly, as under emulation.
      ::execlp("stdbuf", "stdbuf", "-oL", "candump", "-r", "8388608", "-L", "vcan0",
               static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    fd_ = fds[0];
  }
  ~Candump() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
    if (fd_ >= 0) ::close(fd_);
  }
  // Reads lines until one contains `text` or the time is up.
  bool wait_for_line(const std::string& text, std::chrono::milliseconds limit) {
    const auto deadline = Clock::now() + limit;
    while (Clock::now() < deadline) {
      for (const auto& line : lines_) {
        if (line.find(text) != std::string::npos) return true;
      }
      read_some(deadline);
    }
    return false;
  }
  std::size_t count_lines_with(const std::string& text) {
    std::size_t n = 0;
    for (const auto& line : lines_) n += line.find(text) != std::string::npos ? 1 : 0;
    return n;
  }
  void read_some(Clock::time_point deadline) {
    fd_set set;
    FD_ZERO(&set);
    FD_SET(fd_, &set);
    const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - Clock::now());
    struct timeval tv {0, static_cast<suseconds_t>(std::max<int64_t>(0, std::min<int64_t>(left.count(), 100000)))};
    if (::select(fd_ + 1, &set, nullptr, nullptr, &tv) <= 0) return;
    char buf[4096];
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n <= 0) return;
    partial_.append(buf, static_cast<std::size_t>(n));
    std::size_t pos;
    while ((pos = partial_.find('\n')) != std::string::npos) {
      lines_.push_back(partial_.substr(0, pos));
      partial_.erase(0, pos + 1);
    }
  }
  bool running() const { return pid_ > 0 && fd_ >= 0; }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string partial_;
  std::vector<std::string> lines_;
};

CanFrame test_frame(uint32_t n) {
  CanFrame f;
  f.id = 0x1A000000 | n;
  f.size = static_cast<uint8_t>(n % 9);
  for (int i = 0; i < 8; ++i) f.data[i] = static_cast<uint8_t>(n * 7 + i);
  return f;
}

TEST(SocketCanVcan, FramesReachAnotherSocketAndCandump) {
  A3_REQUIRE_VCAN0();
  if (std::system("command -v candump >/dev/null && command -v stdbuf >/dev/null") != 0) {
    GTEST_SKIP() << "candump (Debian package can-utils) or stdbuf not installed";
  }
  ExecutorThread thread;
  auto sender_bus = open_can_bus("vcan0");
  ASSERT_EQ(sender_bus->name(), "socketcan:vcan0") << "the factory picks SocketCAN when vcan0 exists";
  SocketCanBus receiver("vcan0");
  Inbox inbox;
  receiver.start(thread.executor(), inbox.handler());

  Candump candump;
  ASSERT_TRUE(candump.running());
  // candump is ready once it prints a probe frame.
  CanFrame probe;
  probe.extended = false;
  probe.id = 0x7FF;
  probe.size = 1;
  bool ready = false;
  for (int i = 0; i < 100 && !ready; ++i) {
    sender_bus->send(probe);
    ready = candump.wait_for_line("7FF#", 50ms);
  }
  ASSERT_TRUE(ready) << "candump printed nothing";

  // In bursts of 100, each printed by candump before the next: candump is the slow reader.
  constexpr uint32_t kFrames = 500;
  for (uint32_t i = 0; i < kFrames; ++i) {
    ASSERT_TRUE(sender_bus->send(test_frame(i)));
    if (i % 100 == 99) {
      ASSERT_TRUE(candump.wait_for_line(to_cansend_string(test_frame(i)), 20s)) << "frame " << i;
    }
  }
  const auto got = inbox.wait_for(kFrames, 20s);
  std::vector<CanFrame> test_frames;
  for (const auto& f : got) {
    if (f.extended && (f.id & 0x1F000000) == 0x1A000000) test_frames.push_back(f);
  }
  ASSERT_EQ(test_frames.size(), kFrames);
  for (uint32_t i = 0; i < kFrames; ++i) ASSERT_EQ(test_frames[i], test_frame(i)) << "frame " << i;

  // candump -L prints "(time) vcan0 1A0001F3#...": every frame, in cansend syntax.
  ASSERT_TRUE(candump.wait_for_line(to_cansend_string(test_frame(kFrames - 1)), 20s));
  for (uint32_t i = 0; i < kFrames; i += 50) {
    EXPECT_EQ(candump.count_lines_with(" " + to_cansend_string(test_frame(i))), 1u) << i;
  }
  EXPECT_EQ(candump.count_lines_with("vcan0 1A"), kFrames);
  EXPECT_EQ(sender_bus->stats().send_refused, 0u);
}

TEST(SocketCanVcan, CansendFramesReachTheBus) {
  A3_REQUIRE_VCAN0();
  if (std::system("command -v cansend >/dev/null") != 0) GTEST_SKIP() << "cansend not installed";
  ExecutorThread thread;
  SocketCanBus bus("vcan0");
  Inbox inbox;
  bus.start(thread.executor(), inbox.handler());
  ASSERT_EQ(std::system("cansend vcan0 1004062A#000280FFF7C020C5"), 0);
  const auto got = inbox.wait_for(1, 10s);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], *parse_cansend_string("1004062A#000280FFF7C020C5"));
}

TEST(SocketCanVcan, MultiFrameDroneCanTransfersSurvive) {
  A3_REQUIRE_VCAN0();
  ExecutorThread thread;
  SocketCanBus sensor_bus("vcan0");
  SocketCanBus fc_bus("vcan0");
  DroneCanNodeConfig sensor_config;
  sensor_config.node_id = 10;
  DroneCanNodeConfig fc_config;
  fc_config.node_id = 20;
  DroneCanNode sensors(sensor_bus, sensor_config);
  DroneCanNode fc(fc_bus, fc_config);

  std::mutex mutex;
  std::vector<GnssFix2> fixes;
  std::vector<FcStatus> statuses;
  std::vector<AhrsRawImu> imus;
  fc.subscribe<GnssFix2>([&](const GnssFix2& m, const ReceivedTransfer&) {
    std::lock_guard lock(mutex);
    fixes.push_back(m);
  });
  fc.subscribe<AhrsRawImu>([&](const AhrsRawImu& m, const ReceivedTransfer&) {
    std::lock_guard lock(mutex);
    imus.push_back(m);
  });
  fc.subscribe<FcStatus>([&](const FcStatus& m, const ReceivedTransfer&) {
    std::lock_guard lock(mutex);
    statuses.push_back(m);
  });
  sensors.start(thread.executor());
  fc.start(thread.executor());

  constexpr int kRounds = 40;
  for (int i = 0; i < kRounds; ++i) {
    GnssFix2 fix;
    fix.longitude_deg_1e8 = 854170000 + i;
    fix.latitude_deg_1e8 = 4737690000 - i;
    fix.covariance = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    fix.sats_used = static_cast<uint8_t>(i % 64);
    AhrsRawImu imu;
    imu.integration_interval = static_cast<float>(i);
    imu.covariance = {0.5f, 0.5f, 0.5f, 0.25f, 0.25f, 0.25f};
    FcStatus status;
    status.last_command_seq = i;
    status.p_W_m = {1.0f * i, 2.0f, 3.0f};
    ASSERT_TRUE(sensors.publish(fix));
    ASSERT_TRUE(sensors.publish(imu, kPriorityHigh));
    ASSERT_TRUE(sensors.publish(status));
  }
  const auto deadline = Clock::now() + 20s;
  while (Clock::now() < deadline) {
    {
      std::lock_guard lock(mutex);
      if (fixes.size() == kRounds && imus.size() == kRounds && statuses.size() == kRounds) break;
    }
    std::this_thread::sleep_for(5ms);
  }
  fc.stop();
  sensors.stop();
  std::lock_guard lock(mutex);
  ASSERT_EQ(fixes.size(), static_cast<std::size_t>(kRounds));
  ASSERT_EQ(imus.size(), static_cast<std::size_t>(kRounds));
  ASSERT_EQ(statuses.size(), static_cast<std::size_t>(kRounds));
  for (int i = 0; i < kRounds; ++i) {
    EXPECT_EQ(fixes[i].longitude_deg_1e8, 854170000 + i);
    EXPECT_EQ(fixes[i].covariance.size(), 9u);
    EXPECT_EQ(imus[i].integration_interval, static_cast<float>(i));
    EXPECT_EQ(statuses[i].last_command_seq, i);
  }
  EXPECT_EQ(fc.reassembler_stats().rejected_frames(), 0u);
  EXPECT_EQ(fc.reassembler_stats().multi_frame_transfers, 3u * kRounds);
  EXPECT_EQ(fc_bus.stats().receive_overruns, 0u);
}

}  // namespace
}  // namespace a3::bridge
