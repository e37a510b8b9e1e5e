// The real-time threads of a rig's nodes, one per node, each keeping time as the run's sync
// mode wants (DESIGN.md "Time"): free-running, every thread on one wall clock; lockstep, the
// dynamics' thread is the time master (a LockstepPacer granting one flight-controller period
// at a time, acknowledged by the A3_ACTUATORS commands the bridge stamps), the flight
// controller follows the a3.sim.Clock frames the bridge forwards on CAN, and every other node
// follows the A3_CLOCK grants on its own LCM bus, those named by lockstep_followers() answering
// each on A3_CLOCK_ACK. `a3rig run` (all nodes, or the ground side) and `a3rig node part` (one
// part) build their threads here, so both run the same way.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/runtime.hpp"
#include "rigs/run/node_configs.hpp"
#include "rigs/run/rig_nodes.hpp"

namespace a3::rigs {

class RigThreads {
 public:
  // epoch_mono_ns: the CLOCK_MONOTONIC instant of simulated time 0, shared by every process.
  RigThreads(RigNodes& nodes, const RigConfigs& configs, const RunOptions& options, const std::string& lcm_url,
             int64_t epoch_mono_ns);
  ~RigThreads();

  void start();
  // Stops every thread but the first (the recorder, when there is one), newest first.
  void stop_all_but_first();
  void stop_all();
  // "" while every thread runs; else "<node>: <why>".
  std::string failure() const;
  // Simulated time as this process sees it (the first thread's clock).
  const common::RealTimeClock& clock() const;
  std::size_t size() const { return threads_.size(); }

 private:
  std::vector<common::Node*> nodes_;
  std::unique_ptr<common::WallClock> wall_;
  std::vector<std::unique_ptr<common::RealTimeNodeThread>> threads_;
};

// The flight controller's control period: the lockstep quantum.
int64_t lockstep_quantum_us(const RigConfigs& configs);

// The nodes that answer every lockstep grant before the next goes out (besides the flight
// controller, whose answer is its actuator command): those whose outputs reach the vehicle or
// the conversation, so that a starved one delays simulated time instead of acting late in it.
// The recorder and the LCM log only listen; the bridge is in the flight controller's loop.
const std::vector<std::string>& lockstep_followers();

}  // namespace a3::rigs
