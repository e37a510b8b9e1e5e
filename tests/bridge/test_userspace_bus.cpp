// The userspace CAN bus: members get each other's frames (not their own) in order, across
// threads and across processes; a socket left by a crashed member is cleaned up; and the
// factory falls back to it, saying why, where SocketCAN is missing.
#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <thread>
#include <vector>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/can/userspace_bus.hpp"
#include "common/clock.hpp"
#include "common/realtime_executor.hpp"

namespace a3::bridge {
namespace {

using namespace std::chrono_literals;

// A real-time executor on its own thread, as a node would run.
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
  // Waits (generously) until n frames are in.
  std::vector<CanFrame> wait_for(std::size_t n, std::chrono::milliseconds limit = 5000ms) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
      {
        std::lock_guard lock(mutex_);
        if (frames_.size() >= n) return frames_;
      }
      std::this_thread::sleep_for(2ms);
    }
    std::lock_guard lock(mutex_);
    return frames_;
  }
  std::size_t size() {
    std::lock_guard lock(mutex_);
    return frames_.size();
  }

 private:
  std::mutex mutex_;
  std::vector<CanFrame> frames_;
};

CanFrame numbered(uint32_t n) {
  CanFrame f;
  f.id = 0x1000000 | (n & 0xFFFF);
  f.size = 4;
  f.data[0] = static_cast<uint8_t>(n);
  f.data[1] = static_cast<uint8_t>(n >> 8);
  f.data[2] = static_cast<uint8_t>(n >> 16);
  f.data[3] = static_cast<uint8_t>(n >> 24);
  return f;
}

uint32_t number_of(const CanFrame& f) {
  return f.data[0] | (f.data[1] << 8) | (f.data[2] << 16) | (uint32_t(f.data[3]) << 24);
}

class UserspaceBusTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::path("/tmp") / ("a3-ucan-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(root_);
    options_.root = root_;
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  std::filesystem::path root_;
  UserspaceCanOptions options_;
};

TEST_F(UserspaceBusTest, MembersHearEachOtherInOrderButNotThemselves) {
  ExecutorThread thread;
  UserspaceCanBus a("bus0", options_);
  UserspaceCanBus b("bus0", options_);
  UserspaceCanBus c("bus0", options_);
  Inbox in_a, in_b, in_c;
  a.start(thread.executor(), in_a.handler());
  b.start(thread.executor(), in_b.handler());
  c.start(thread.executor(), in_c.handler());
  // The earlier members learn of later ones when they accept their connections.
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while ((a.peer_count() < 2 || b.peer_count() < 2) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(a.peer_count(), 2u);
  ASSERT_EQ(b.peer_count(), 2u);
  ASSERT_EQ(c.peer_count(), 2u);

  constexpr uint32_t kFrames = 3000;
  for (uint32_t i = 0; i < kFrames; ++i) ASSERT_TRUE(a.send(numbered(i)));
  ASSERT_TRUE(c.send(numbered(999999)));
  const auto at_b = in_b.wait_for(kFrames + 1);
  ASSERT_EQ(at_b.size(), kFrames + 1);
  const auto at_c = in_c.wait_for(kFrames);
  ASSERT_EQ(at_c.size(), kFrames);
  for (uint32_t i = 0; i < kFrames; ++i) ASSERT_EQ(number_of(at_c[i]), i) << "in order";
  EXPECT_EQ(in_a.wait_for(1).size(), 1u) << "a hears c, not itself";
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(in_a.size(), 1u);
  EXPECT_EQ(a.stats().frames_sent, kFrames);
  EXPECT_EQ(a.stats().send_refused, 0u);
}

TEST_F(UserspaceBusTest, ASendOnlyMemberReachesMembersThatJoinLater) {
  // The sender never calls start(): its I/O thread still accepts the later member.
  UserspaceCanBus sender("bus2", options_);
  ExecutorThread thread;
  UserspaceCanBus listener("bus2", options_);
  Inbox inbox;
  listener.start(thread.executor(), inbox.handler());
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  while (sender.peer_count() < 1 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(sender.peer_count(), 1u);
  for (uint32_t i = 0; i < 5000; ++i) ASSERT_TRUE(sender.send(numbered(i)));
  const auto got = inbox.wait_for(5000);
  ASSERT_EQ(got.size(), 5000u);
  EXPECT_EQ(number_of(got.back()), 4999u);
}

TEST_F(UserspaceBusTest, FramesCrossProcesses) {
  // The child echoes every frame back with its number + 1 until it sees number 0xFFFFFFFF.
  std::filesystem::create_directories(root_);
  int ready_pipe[2];
  ASSERT_EQ(::pipe(ready_pipe), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    int status = 1;
    {
      ExecutorThread thread;
      UserspaceCanBus bus("xproc", options_);
      std::atomic<bool> done{false};
      bus.start(thread.executor(), [&](const CanFrame& f, int64_t) {
        if (number_of(f) == 0xFFFFFFFFu) {
          done = true;
          return;
        }
        bus.send(numbered(number_of(f) + 1));
      });
      const char ready = 'r';
      [[maybe_unused]] auto n = ::write(ready_pipe[1], &ready, 1);
      for (int i = 0; i < 10000 && !done; ++i) std::this_thread::sleep_for(1ms);
      status = done ? 0 : 3;
      bus.stop();
    }
    ::_exit(status);
  }
  char ready = 0;
  ASSERT_EQ(::read(ready_pipe[0], &ready, 1), 1);
  ExecutorThread thread;
  UserspaceCanBus bus("xproc", options_);
  ASSERT_EQ(bus.peer_count(), 1u) << "joined the child's bus";
  Inbox inbox;
  bus.start(thread.executor(), inbox.handler());
  constexpr uint32_t kFrames = 2000;
  for (uint32_t i = 0; i < kFrames; ++i) ASSERT_TRUE(bus.send(numbered(i * 10)));
  const auto echoes = inbox.wait_for(kFrames);
  ASSERT_TRUE(bus.send(numbered(0xFFFFFFFFu)));
  int status = -1;
  ::waitpid(child, &status, 0);
  ASSERT_EQ(echoes.size(), kFrames);
  for (uint32_t i = 0; i < kFrames; ++i) ASSERT_EQ(number_of(echoes[i]), i * 10 + 1);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST_F(UserspaceBusTest, ASocketLeftByACrashedMemberIsRemoved) {
  std::filesystem::path stale;
  {
    UserspaceCanBus gone("bus1", options_);
    stale = gone.socket_path();
  }
  // Simulate the crash: a socket file nobody listens on (the folder went with its last member).
  std::filesystem::create_directories(stale.parent_path());
  {
    const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET, 0);
    struct sockaddr_un addr {};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, stale.c_str(), sizeof addr.sun_path - 1);
    ASSERT_EQ(::bind(fd, reinterpret_cast<struct sockaddr*>(&addr), sizeof addr), 0);
    ::close(fd);  // bound, never listening, closed: what a killed process leaves
  }
  ASSERT_TRUE(std::filesystem::exists(stale));
  UserspaceCanBus next("bus1", options_);
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_EQ(next.peer_count(), 0u);
}

TEST_F(UserspaceBusTest, BadNamesAreRefusedWithTheReason) {
  try {
    UserspaceCanBus bus("../etc", options_);
    FAIL() << "accepted a path as a bus name";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'../etc' must be"), std::string::npos) << e.what();
  }
}

TEST(CanBusFactory, FallsBackToTheUserspaceBusSayingWhy) {
  const std::string why = SocketCanBus::probe("vcan0");
  const CanTransportChoice choice = choose_can_transport("vcan0");
  if (why.empty()) {
    EXPECT_EQ(choice.transport, CanTransport::kSocketCan) << "vcan0 exists here";
    return;
  }
  EXPECT_EQ(choice.transport, CanTransport::kUserspace);
  EXPECT_TRUE(choice.fell_back);
  EXPECT_EQ(choice.reason, why);
  EXPECT_TRUE(why.find("no SocketCAN") != std::string::npos ||
              why.find("no network interface named vcan0") != std::string::npos ||
              why.find("is down") != std::string::npos)
      << why;
}

TEST(CanBusFactory, ExplicitKinds) {
  EXPECT_EQ(choose_can_transport("userspace:sim").transport, CanTransport::kUserspace);
  EXPECT_FALSE(choose_can_transport("userspace:sim").fell_back);
  EXPECT_THROW(choose_can_transport("carrier-pigeon:x"), std::invalid_argument);
  EXPECT_THROW(choose_can_transport(""), std::invalid_argument);
  const CanTransportChoice forced = choose_can_transport("socketcan:a3nosuch0");
  EXPECT_EQ(forced.transport, CanTransport::kSocketCan);
  try {
    open_can_bus("socketcan:a3nosuch0");
    FAIL() << "opened a missing interface";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a3nosuch0"), std::string::npos) << e.what();
  }
}

TEST(CanFrameText, SocketCanBytesAndCansendSyntax) {
  CanFrame f;
  f.id = 0x1004062A;
  f.size = 3;
  f.data[0] = 0xDE;
  f.data[1] = 0xAD;
  f.data[2] = 0x01;
  uint8_t raw[kSocketCanFrameBytes];
  to_socketcan_bytes(f, raw);
  EXPECT_EQ(raw[3], 0x90) << "CAN_EFF_FLAG | top bits of the ID, little-endian can_id";
  EXPECT_EQ(raw[4], 3) << "len";
  EXPECT_EQ(raw[8], 0xDE);
  const auto back = from_socketcan_bytes(raw, sizeof raw);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(*back, f);
  raw[4] = 9;
  EXPECT_FALSE(from_socketcan_bytes(raw, sizeof raw).has_value()) << "length 9 is not classic CAN";
  EXPECT_FALSE(from_socketcan_bytes(raw, 15).has_value());

  EXPECT_EQ(to_cansend_string(f), "1004062A#DEAD01");
  const auto parsed = parse_cansend_string("1004062A#DE.AD.01");
  ASSERT_TRUE(parsed.has_value());
  EXPECT_EQ(*parsed, f);
  std::string error;
  EXPECT_FALSE(parse_cansend_string("12345#00", &error).has_value());
  EXPECT_NE(error.find("3 hex digits (standard) or 8 (extended)"), std::string::npos) << error;
  EXPECT_FALSE(parse_cansend_string("123#0011223344556677AA", &error).has_value());
  EXPECT_FALSE(parse_cansend_string("123#G0", &error).has_value());
  EXPECT_EQ(parse_cansend_string("7FF#R")->remote, true);
}

}  // namespace
}  // namespace a3::bridge
