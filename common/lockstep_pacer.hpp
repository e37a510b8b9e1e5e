// The lockstep time master of the real-time runtime (DESIGN.md "Time"; PX4's lockstep
// simulation): it grants simulated time one quantum (the flight controller's control period)
// at a time, publishing each grant as sim_clock_t on A3_CLOCK, and it grants t + quantum only
// when all of these hold:
//   - the vehicle's loop has closed for the step at t: note_ack(t) was called (the rig calls
//     it for each A3_ACTUATORS command, which the bridge stamps with the grant under which the
//     flight controller produced it),
//   - every follower named in the configuration has run what was due at t: note_follower_ack
//     (the rig calls it for each clock_ack_t on A3_CLOCK_ACK), so that a starved link emulator,
//     tool server or conversation delays simulated time instead of acting late in it,
//   - no follower has published anything since the answers before: what one said at t, others
//     must hear at t too (a tool call delivered at t is executed at t). While some did, t is
//     granted again in a new round (sim_clock_t.round), and answered again, until a round
//     passes in silence, and
//   - the wall clock has reached t + quantum at the requested real-time factor.
// A late host therefore slows simulated time down instead of leaving the physics without
// commands. Wall-clock lag up to max_catch_up_s is made up by granting faster; lag beyond it
// is let go (the achieved factor drops), so that a stall is never followed by a burst.
// Grants before first_ack_us need no acknowledgement (the controller's first step comes at
// one quantum). It drives the clock of the executor it is attached to (ClockDriver), so the
// nodes of that executor (the dynamics) run first at each new time, then the grant goes out:
// a state published at t always precedes the grant of t on the bus.
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "common/bus.hpp"
#include "common/clock.hpp"
#include "common/clock_driver.hpp"

namespace a3::common {

struct LockstepConfig {
  int64_t quantum_us = 4000;
  double real_time_factor = 1.0;
  int64_t start_mono_ns = -1;  // wall instant of the clock's start time; < 0: now
  int64_t first_ack_us = 0;    // grants up to here need no acknowledgement
  double max_catch_up_s = 0.1;
  double window_s = 1.0;       // the window of the worst-window factor
  std::string channel;         // default A3_CLOCK
  std::vector<std::string> followers;  // node names whose answer every grant waits for
};

struct LockstepStats {
  int64_t granted_us = 0;
  uint64_t grants = 0;
  uint64_t rounds = 0;           // grants of a time again, for what followers said at it
  uint64_t waits = 0;            // grants held past their wall time by a missing acknowledgement
  double wait_total_s = 0.0;     // wall time those grants were held
  double wait_max_s = 0.0;
  std::map<std::string, double> wait_on_s;  // that wall time by the node answering last ("fc": the vehicle)
  double lag_dropped_s = 0.0;    // wall lag beyond the catch-up window, let go
  double achieved_rtf = 0.0;     // simulated s per wall s since the start
  double worst_window_rtf = -1.0;  // lowest over whole windows of window_s wall; < 0: none yet
  double wall_s = 0.0;
};

class LockstepPacer final : public ClockDriver {
 public:
  // Both must outlive the pacer; bus is where grants are published.
  LockstepPacer(SteppedClock& clock, Bus& bus, LockstepConfig config);

  // The vehicle's answer (an actuator command computed under the grant utime_us).
  void note_ack(int64_t utime_us);
  // A follower's answer to the grant of utime_us in round `round`, with the number of messages
  // it has published so far; names not in the configuration are ignored.
  void note_follower_ack(const std::string& node, int64_t utime_us, int32_t round, int64_t messages_published);
  bool poll(int64_t mono_now_ns) override;
  void after_due_timers() override;
  std::optional<int64_t> next_poll_mono_ns() const override;
  // Safe from any thread.
  LockstepStats stats() const;
  const LockstepConfig& config() const { return config_; }

 private:
  int64_t target_mono_ns(int64_t sim_us) const;
  bool vehicle_acked(int64_t granted_us) const { return granted_us < config_.first_ack_us || ack_us_ >= granted_us; }
  bool acked(int64_t granted_us) const;
  bool followers_spoke() const;
  void start_round(int64_t t_us, int64_t mono_now_ns);
  void account_hold(const std::string& last_answer);
  void account_window(int64_t mono_now_ns, int64_t sim_us);
  void publish(int64_t t_us, int64_t mono_now_ns);

  SteppedClock& clock_;
  Bus& bus_;
  LockstepConfig config_;
  int64_t base_mono_ns_;   // pacing: sim base_sim_us_ is due at base_mono_ns_
  int64_t base_sim_us_;
  int64_t start_mono_ns_;
  int64_t start_sim_us_;
  int64_t ack_us_ = INT64_MIN;
  struct FollowerAnswer {
    int64_t utime_us = INT64_MIN;  // the latest grant answered, and its round
    int32_t round = 0;
    int64_t said = 0;              // messages published, by that answer
    int64_t said_before = 0;       // by the answers of the round before
  };
  std::vector<FollowerAnswer> followers_;  // by config_.followers' index
  int32_t round_ = 0;                      // of the current time's grant
  int64_t hold_accounted_us_ = INT64_MIN;  // the grant whose answers are all in and counted
  int64_t published_us_ = INT64_MIN;
  int64_t publish_mono_ns_ = 0;       // when the current time's grant first went out
  int64_t last_publish_mono_ns_ = 0;  // when it last went out (republished while unanswered)
  int64_t window_mono_ns_, window_sim_us_;
  mutable std::mutex stats_mutex_;
  LockstepStats stats_;
};

}  // namespace a3::common
