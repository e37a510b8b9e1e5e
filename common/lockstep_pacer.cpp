// The lockstep time master.
#include "common/lockstep_pacer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "a3lcm/sim_clock_t.hpp"
#include "common/channels.hpp"

namespace a3::common {
namespace {

// A grant the vehicle has not answered is published again this often, so that one lost
// datagram cannot stall the loop.
constexpr int64_t kRepublish_ns = 20'000'000;

}  // namespace

LockstepPacer::LockstepPacer(SteppedClock& clock, Bus& bus, LockstepConfig config)
    : clock_(clock), bus_(bus), config_(std::move(config)) {
  if (config_.quantum_us <= 0) {
    throw std::invalid_argument("lockstep: quantum must be > 0 us, got " + std::to_string(config_.quantum_us));
  }
  if (!(config_.real_time_factor > 0.0) || !std::isfinite(config_.real_time_factor)) {
    throw std::invalid_argument("lockstep: real-time factor must be a positive number");
  }
  if (config_.channel.empty()) config_.channel = channels::kClock.name;
  followers_.assign(config_.followers.size(), FollowerAnswer{});
  start_mono_ns_ = base_mono_ns_ = config_.start_mono_ns >= 0 ? config_.start_mono_ns : WallClock::monotonic_now_ns();
  start_sim_us_ = base_sim_us_ = clock_.now_us();
  window_mono_ns_ = start_mono_ns_;
  window_sim_us_ = start_sim_us_;
  stats_.granted_us = start_sim_us_;
}

int64_t LockstepPacer::target_mono_ns(int64_t sim_us) const {
  return base_mono_ns_ +
         static_cast<int64_t>(std::ceil(static_cast<double>(sim_us - base_sim_us_) * 1e3 / config_.real_time_factor));
}

void LockstepPacer::note_ack(int64_t utime_us) {
  if (utime_us <= ack_us_) return;
  ack_us_ = utime_us;
  account_hold("fc");
}

void LockstepPacer::note_follower_ack(const std::string& node, int64_t utime_us, int32_t round,
                                      int64_t messages_published) {
  const auto it = std::find(config_.followers.begin(), config_.followers.end(), node);
  if (it == config_.followers.end()) return;
  FollowerAnswer& f = followers_[static_cast<std::size_t>(it - config_.followers.begin())];
  if (utime_us < f.utime_us || (utime_us == f.utime_us && round < f.round)) return;  // an old answer
  f.utime_us = utime_us;
  f.round = round;
  f.said = std::max(f.said, messages_published);
  account_hold(node);
}

bool LockstepPacer::acked(int64_t granted_us) const {
  if (!vehicle_acked(granted_us)) return false;
  return std::all_of(followers_.begin(), followers_.end(), [&](const FollowerAnswer& f) {
    return f.utime_us > granted_us || (f.utime_us == granted_us && f.round >= round_);
  });
}

bool LockstepPacer::followers_spoke() const {
  return std::any_of(followers_.begin(), followers_.end(), [](const FollowerAnswer& f) { return f.said != f.said_before; });
}

void LockstepPacer::start_round(int64_t t_us, int64_t mono_now_ns) {
  for (FollowerAnswer& f : followers_) f.said_before = f.said;
  ++round_;
  {
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++stats_.rounds;
  }
  publish(t_us, mono_now_ns);
}

// Once every answer to the current grant is in: was the grant held past its wall time waiting
// for them, and whose answer came last?
void LockstepPacer::account_hold(const std::string& last_answer) {
  const int64_t granted = clock_.now_us();
  if (published_us_ != granted || hold_accounted_us_ == granted || !acked(granted) || followers_spoke()) return;
  hold_accounted_us_ = granted;
  const int64_t now_ns = WallClock::monotonic_now_ns();
  const int64_t ready_ns = std::max(target_mono_ns(granted + config_.quantum_us), publish_mono_ns_);
  if (now_ns <= ready_ns) return;
  const double held_s = static_cast<double>(now_ns - ready_ns) * 1e-9;
  std::lock_guard<std::mutex> lock(stats_mutex_);
  ++stats_.waits;
  stats_.wait_total_s += held_s;
  stats_.wait_max_s = std::max(stats_.wait_max_s, held_s);
  stats_.wait_on_s[last_answer] += held_s;
}

std::optional<int64_t> LockstepPacer::next_poll_mono_ns() const {
  const int64_t t = clock_.now_us();
  if (published_us_ != t) return WallClock::monotonic_now_ns();
  if (!acked(t)) return last_publish_mono_ns_ + kRepublish_ns;
  if (followers_spoke()) return WallClock::monotonic_now_ns();
  return target_mono_ns(t + config_.quantum_us);
}

bool LockstepPacer::poll(int64_t mono_now_ns) {
  const int64_t t = clock_.now_us();
  if (published_us_ != t) return false;  // the current time's grant is not out yet
  if (!acked(t)) {
    if (mono_now_ns - last_publish_mono_ns_ >= kRepublish_ns) publish(t, mono_now_ns);
    return false;
  }
  if (followers_spoke()) {
    start_round(t, mono_now_ns);
    return false;
  }
  const int64_t next = t + config_.quantum_us;
  const int64_t due_ns = target_mono_ns(next);
  if (mono_now_ns < due_ns) return false;
  const auto max_lag_ns = static_cast<int64_t>(config_.max_catch_up_s * 1e9);
  if (mono_now_ns - due_ns > max_lag_ns) {
    // Too far behind to catch up: let the lag go, simulated time is slower from here on.
    const int64_t dropped_ns = mono_now_ns - due_ns - max_lag_ns;
    base_mono_ns_ += dropped_ns;
    std::lock_guard<std::mutex> lock(stats_mutex_);
    stats_.lag_dropped_s += static_cast<double>(dropped_ns) * 1e-9;
  }
  round_ = 0;
  clock_.advance_to(next);
  return true;
}

void LockstepPacer::after_due_timers() {
  const int64_t t = clock_.now_us();
  if (published_us_ == t) return;
  const int64_t now_ns = WallClock::monotonic_now_ns();
  publish_mono_ns_ = now_ns;
  publish(t, now_ns);
  published_us_ = t;
  account_window(now_ns, t);
}

void LockstepPacer::publish(int64_t t_us, int64_t mono_now_ns) {
  last_publish_mono_ns_ = mono_now_ns;
  a3lcm::sim_clock_t msg{};
  msg.utime_us = t_us;
  msg.wall_utime_us = target_mono_ns(t_us) / 1000;
  msg.real_time_factor = config_.real_time_factor;
  msg.round = round_;
  const double wall_s = static_cast<double>(mono_now_ns - start_mono_ns_) * 1e-9;
  msg.achieved_real_time_factor = wall_s > 0.0 ? static_cast<double>(t_us - start_sim_us_) * 1e-6 / wall_s : 0.0;
  bus_.publish(config_.channel, msg);
}

void LockstepPacer::account_window(int64_t mono_now_ns, int64_t sim_us) {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  ++stats_.grants;
  stats_.granted_us = sim_us;
  stats_.wall_s = static_cast<double>(mono_now_ns - start_mono_ns_) * 1e-9;
  stats_.achieved_rtf = stats_.wall_s > 0.0 ? static_cast<double>(sim_us - start_sim_us_) * 1e-6 / stats_.wall_s : 0.0;
  const double window_wall_s = static_cast<double>(mono_now_ns - window_mono_ns_) * 1e-9;
  if (window_wall_s >= config_.window_s) {
    const double rtf = static_cast<double>(sim_us - window_sim_us_) * 1e-6 / window_wall_s;
    stats_.worst_window_rtf = stats_.worst_window_rtf < 0.0 ? rtf : std::min(stats_.worst_window_rtf, rtf);
    window_mono_ns_ = mono_now_ns;
    window_sim_us_ = sim_us;
  }
}

LockstepStats LockstepPacer::stats() const {
  std::lock_guard<std::mutex> lock(stats_mutex_);
  return stats_;
}

}  // namespace a3::common
