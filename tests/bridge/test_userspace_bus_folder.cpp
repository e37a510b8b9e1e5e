// The userspace CAN bus leaves nothing behind (issue 14): the last member to leave removes the
// bus's folder; a bus whose last member crashed (a killed process: its socket file stays) is
// removed by remove_userspace_can_bus_if_unused, as `a3rig run` does at exit; members joining
// while the last one leaves always get a working bus. Label "faults": members crash on purpose.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "bridge/can/userspace_bus.hpp"
#include "bridge/can/userspace_bus_folder.hpp"

namespace a3::bridge {
namespace {

class UserspaceBusFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::path("/tmp") / ("a3-ucan-folder-test-" + std::to_string(::getpid()));
    std::filesystem::remove_all(root_);
    options_.root = root_;
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  std::filesystem::path bus_dir(const std::string& name) const { return root_ / name; }
  std::filesystem::path root_;
  UserspaceCanOptions options_;
};

TEST_F(UserspaceBusFolder, TheLastMemberToLeaveRemovesIt) {
  auto a = std::make_unique<UserspaceCanBus>("bus", options_);
  auto b = std::make_unique<UserspaceCanBus>("bus", options_);
  ASSERT_TRUE(std::filesystem::exists(bus_dir("bus") / ".lock"));
  a.reset();
  EXPECT_TRUE(std::filesystem::exists(bus_dir("bus"))) << "b is still on the bus";
  EXPECT_TRUE(std::filesystem::exists(b->socket_path()));
  b.reset();
  EXPECT_FALSE(std::filesystem::exists(bus_dir("bus")));
}

TEST_F(UserspaceBusFolder, ABusWhoseLastMemberCrashedIsRemovedByWhoeverStartedIt) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    new UserspaceCanBus("crashed", options_);  // never destroyed: the process dies with it
    ::_exit(0);
  }
  int status = -1;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(std::filesystem::exists(bus_dir("crashed") / ".lock")) << "the crash left the folder";
  EXPECT_TRUE(remove_userspace_can_bus_if_unused(bus_dir("crashed")));
  EXPECT_FALSE(std::filesystem::exists(bus_dir("crashed")));
  EXPECT_TRUE(remove_userspace_can_bus_if_unused(bus_dir("crashed"))) << "nothing to remove is no error";
}

TEST_F(UserspaceBusFolder, ABusWithAMemberIsNotRemoved) {
  UserspaceCanBus member("alive", options_);
  EXPECT_FALSE(remove_userspace_can_bus_if_unused(bus_dir("alive")));
  EXPECT_TRUE(std::filesystem::exists(member.socket_path()));
  UserspaceCanBus later("alive", options_);
  EXPECT_EQ(later.peer_count(), 1u) << "the member still listens";
}

TEST_F(UserspaceBusFolder, MembersThatComeAndGoAtOnceAlwaysJoin) {
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 100; ++i) {
        try {
          UserspaceCanBus bus("churn", options_);
          if (!std::filesystem::exists(bus.socket_path())) ++failures;
        } catch (const std::exception&) {
          ++failures;
        }
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_FALSE(std::filesystem::exists(bus_dir("churn")));
}

// A child process that joins the bus and dies without leaving (as a killed process does).
void crash_on_bus(const std::string& name, const UserspaceCanOptions& options) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    new UserspaceCanBus(name, options);
    ::_exit(0);
  }
  int status = -1;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
}

TEST_F(UserspaceBusFolder, TheRunsGuardRemovesItsBusAfterAChildCrashed) {
  const std::string name = "a3rig-run-" + std::to_string(::getpid());
  {
    const UserspaceBusFolderGuard guard("userspace:" + name, options_);
    EXPECT_EQ(guard.directory(), bus_dir(name));
    crash_on_bus(name, options_);
    ASSERT_TRUE(std::filesystem::exists(bus_dir(name) / ".lock"));
  }
  EXPECT_FALSE(std::filesystem::exists(bus_dir(name)));
}

TEST_F(UserspaceBusFolder, TheRunsGuardRemovesTheFoldersOfRunsThatWereKilled) {
  // Runs 999999990.. are not processes (pid_max is at most 4194304); 1 is init, alive.
  crash_on_bus("a3rig-run-999999990", options_);
  crash_on_bus("a3rig-run-1", options_);
  crash_on_bus("other-999999991", options_);
  ASSERT_TRUE(std::filesystem::exists(bus_dir("a3rig-run-999999990")));
  const UserspaceBusFolderGuard guard("userspace:a3rig-run-" + std::to_string(::getpid()), options_);
  EXPECT_FALSE(std::filesystem::exists(bus_dir("a3rig-run-999999990")));
  EXPECT_TRUE(std::filesystem::exists(bus_dir("a3rig-run-1"))) << "its process is alive";
  EXPECT_TRUE(std::filesystem::exists(bus_dir("other-999999991"))) << "not this program's kind of bus";
}

TEST_F(UserspaceBusFolder, AGuardOfAnotherKindOfBusDoesNothing) {
  EXPECT_TRUE(UserspaceBusFolderGuard("socketcan:can0", options_).directory().empty());
  EXPECT_TRUE(UserspaceBusFolderGuard("bogus:x", options_).directory().empty());
}

}  // namespace
}  // namespace a3::bridge
