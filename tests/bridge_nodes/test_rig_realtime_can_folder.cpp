// `a3rig run` in real time leaves no userspace CAN bus folder behind (issue 14: 41 a3rig-run-<pid>
// folders had accumulated): not when SIGTERM stops it (the normal teardown runs), not when its
// fc child process is killed in --processes mode (the parent removes the crashed member's bus).
// Each run uses a private bus root ($A3_CAN_USERSPACE_DIR, inherited by a3rig). Labels
// "realtime" and "faults"; RUN_SERIAL (about 10-30 s of wall time each).
#include <gtest/gtest.h>

#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/integration/run_command.hpp"
#include "tests/rigs/real_time_support.hpp"

namespace a3::bridge {
namespace {

namespace fs = std::filesystem;
using a3::test::RunningRig;

class RunCanFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::path("/tmp") / ("a3cf-" + std::to_string(::getpid()));
    fs::remove_all(root_);
    fs::create_directories(root_);
    ::setenv("A3_CAN_USERSPACE_DIR", root_.c_str(), 1);
  }
  void TearDown() override {
    ::unsetenv("A3_CAN_USERSPACE_DIR");
    fs::remove_all(root_);
  }
  // The a3rig-run-* folders under the bus root, by name.
  std::string run_folders() const {
    std::string names;
    for (const auto& e : fs::directory_iterator(root_)) {
      if (e.path().filename().string().rfind("a3rig-run-", 0) == 0) names += e.path().filename().string() + " ";
    }
    return names;
  }
  RunningRig start(const std::string& tag, std::vector<std::string> extra) {
    std::vector<std::string> args = {a3::test::a3rig(), "run", "--scenario", "survey-field", "--rtf", "2",
                                     "--out", (root_ / (tag + "-out")).string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return RunningRig(args, root_ / (tag + "-output.txt"));
  }
  fs::path root_;
};

TEST_F(RunCanFolder, SigtermStopsTheRunAndItsBusFolderGoes) {
  A3_REQUIRE_MULTICAST();
  RunningRig rig = start("sigterm", {});
  ASSERT_TRUE(rig.wait_for_output("turn  2", 90.0)) << rig.text();
  EXPECT_NE(run_folders(), "") << "the run's bus is a folder while it runs";
  ::kill(rig.pid, SIGTERM);
  EXPECT_EQ(rig.wait_exit(60.0), 3) << rig.text();  // interrupted
  EXPECT_EQ(run_folders(), "") << rig.text();
}

TEST_F(RunCanFolder, AKilledFcProcessDoesNotLeaveTheBusFolderBehind) {
  A3_REQUIRE_MULTICAST();
  RunningRig rig = start("processes", {"--processes"});
  ASSERT_TRUE(rig.wait_for_output("turn  2", 90.0)) << rig.text();
  const pid_t run_pid = rig.pid;
  const pid_t fc = a3::test::part_of_run(run_pid, "fc");
  ASSERT_GT(fc, 0) << "no `a3rig node part fc` process of run " << run_pid;
  ::kill(fc, SIGKILL);  // its socket file stays: a crashed member
  EXPECT_EQ(rig.wait_exit(60.0), 4) << rig.text();  // node_failed: fc
  EXPECT_EQ(run_folders(), "") << rig.text();
}

}  // namespace
}  // namespace a3::bridge
