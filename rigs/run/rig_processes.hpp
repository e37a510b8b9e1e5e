// `a3rig run --processes`: every part of the rig except the ground side runs as a process of
// its own (`a3rig node part NAME`), talking to the others only through LCM (UDP multicast)
// and the CAN bus. The children are started, each builds its nodes from the same scenario
// and options and says "ready" on its stdout; then all are told the same clock epoch on
// their stdin ("go <CLOCK_MONOTONIC ns>") so that every process agrees on simulated time.
// A child that dies is reported by name; at the end each gets SIGTERM (then SIGKILL).
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rigs/run/rig_nodes.hpp"
#include "rigs/run/run_options.hpp"

namespace a3::rigs {

class RigProcesses {
 public:
  // Starts `exe node part NAME ...` for each part. Throws std::runtime_error naming the part
  // that could not be started.
  RigProcesses(const std::filesystem::path& exe, const std::vector<RigPart>& parts, const RunOptions& options,
               const std::string& lcm_url, const std::string& can_spec);
  ~RigProcesses();
  RigProcesses(const RigProcesses&) = delete;
  RigProcesses& operator=(const RigProcesses&) = delete;

  // Waits until every child said "ready": "" when all did, else which did not and why.
  std::string wait_ready(double timeout_s);
  // Gives every child the clock epoch.
  void go(int64_t epoch_mono_ns);
  // "" while every child runs; else "<part> (pid N) exited with status S" or "... killed by signal S".
  std::string check();
  // SIGTERM to every child still running, then SIGKILL after grace_s; reaps them all.
  void stop(double grace_s = 3.0);

  // The arguments a child gets after the program name (for logs and tests).
  static std::vector<std::string> child_arguments(RigPart part, const RunOptions& options, const std::string& lcm_url,
                                                  const std::string& can_spec);

 private:
  struct Child {
    RigPart part;
    pid_t pid = -1;
    int ready_fd = -1;  // its stdout
    int go_fd = -1;     // its stdin
    bool ready = false;
    bool exited = false;
    int wait_status = 0;
  };
  std::vector<Child> children_;
  static std::string describe_exit(const Child& c);
};

}  // namespace a3::rigs
