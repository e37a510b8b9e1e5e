// Real-time threads of a rig.
#include "rigs/run/rig_threads.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "a3lcm/actuator_cmd_t.hpp"
#include "common/channels.hpp"

namespace a3::rigs {

const char* to_string(Sync sync) { return sync == Sync::kLockstep ? "lockstep" : "free"; }

int64_t lockstep_quantum_us(const RigConfigs& configs) {
  return std::llround(1e6 / configs.agent_vehicle().fc.params.control_rate_hz);
}

const std::vector<std::string>& lockstep_followers() {
  static const std::vector<std::string> names = {"linkemu", "tool_server", "airspace_monitor", "conversation"};
  return names;
}

namespace {

common::ThreadClock thread_clock(const common::Node* node, const RigNodes& n, const RigConfigs& cfg,
                                 const RunOptions& o, const common::WallClock* wall, int64_t epoch_mono_ns) {
  common::ThreadClock how;
  if (o.sync == Sync::kFree) {
    how = common::ThreadClock::free_running(*wall);
  } else if (node == n.agent_vehicle().dynamics.get()) {
    common::LockstepConfig pacing;
    pacing.quantum_us = lockstep_quantum_us(cfg);
    pacing.real_time_factor = o.real_time_factor;
    pacing.start_mono_ns = epoch_mono_ns;
    pacing.first_ack_us = pacing.quantum_us;
    pacing.followers = lockstep_followers();
    how = common::ThreadClock::master(pacing);
  } else if (node == n.agent_vehicle().fc.get()) {
    how = common::ThreadClock::external();
  } else {
    const auto& followers = lockstep_followers();
    how = common::ThreadClock::follower(std::find(followers.begin(), followers.end(), node->name()) != followers.end());
  }
  // A deadline miss: a timer later than one control period of wall time.
  how.deadline_miss_us = static_cast<double>(lockstep_quantum_us(cfg)) / o.real_time_factor;
  return how;
}

// The whole rig in this process: a follower the pacer waits for but nobody runs would stop
// simulated time at its first grant.
void check_followers_present(const std::vector<common::Node*>& nodes) {
  for (const std::string& name : lockstep_followers()) {
    const bool present = std::any_of(nodes.begin(), nodes.end(), [&](const common::Node* node) { return node->name() == name; });
    if (!present) throw std::logic_error("lockstep: the follower '" + name + "' is not a node of this rig");
  }
}

}  // namespace

RigThreads::RigThreads(RigNodes& n, const RigConfigs& cfg, const RunOptions& o, const std::string& lcm_url,
                       int64_t epoch_mono_ns)
    : nodes_(n.in_start_order()) {
  // Lockstep paces one vehicle's physics against its fc and its followers (by node name).
  if (n.vehicles.size() != 1) throw std::invalid_argument("real time flies one vehicle (several: virtual time)");
  VehicleNodes& v = n.agent_vehicle();
  if (v.dynamics && n.conversation) check_followers_present(nodes_);
  if (o.sync == Sync::kFree) wall_ = std::make_unique<common::WallClock>(o.real_time_factor, epoch_mono_ns);
  for (common::Node* node : nodes_) {
    auto th = std::make_unique<common::RealTimeNodeThread>(*node, thread_clock(node, n, cfg, o, wall_.get(), epoch_mono_ns),
                                                           lcm_url);
    if (common::LockstepPacer* pacer = th->pacer()) {
      th->bus().subscribe<a3lcm::actuator_cmd_t>(
          common::channels::kActuators.of(cfg.agent_vehicle().vehicle_id()),
          [pacer](const a3lcm::actuator_cmd_t& m, int64_t) { pacer->note_ack(m.utime_us); });
    }
    if (node == v.fc.get() && o.sync == Sync::kLockstep) v.fc->follow_sim_clock(th->stepped_clock());
    threads_.push_back(std::move(th));
  }
}

RigThreads::~RigThreads() { stop_all(); }

void RigThreads::start() {
  for (auto& th : threads_) th->start();
}

void RigThreads::stop_all_but_first() {
  for (std::size_t i = threads_.size(); i-- > 1;) threads_[i]->stop_and_join();
}

void RigThreads::stop_all() {
  for (std::size_t i = threads_.size(); i-- > 0;) threads_[i]->stop_and_join();
}

std::string RigThreads::failure() const {
  for (std::size_t i = 0; i < threads_.size(); ++i) {
    if (const std::string why = threads_[i]->failure(); !why.empty()) return nodes_[i]->name() + ": " + why;
  }
  return "";
}

const common::RealTimeClock& RigThreads::clock() const {
  if (threads_.empty()) throw std::logic_error("RigThreads: no threads");
  return threads_.front()->clock();
}

}  // namespace a3::rigs
