// Real-time node threads.
#include "common/runtime.hpp"

#include <exception>

#include "a3lcm/clock_ack_t.hpp"
#include "a3lcm/sim_clock_t.hpp"
#include "common/channels.hpp"
#include "common/node_stats.hpp"

namespace a3::common {

ThreadClock ThreadClock::free_running(const WallClock& clock) {
  ThreadClock c;
  c.kind = Kind::kWall;
  c.wall = &clock;
  return c;
}

ThreadClock ThreadClock::master(LockstepConfig pacing) {
  ThreadClock c;
  c.kind = Kind::kLockstepMaster;
  c.pacing = std::move(pacing);
  return c;
}

ThreadClock ThreadClock::follower(bool acknowledges) {
  ThreadClock c;
  c.kind = Kind::kLockstepFollower;
  c.acknowledges = acknowledges;
  return c;
}

ThreadClock ThreadClock::external() {
  ThreadClock c;
  c.kind = Kind::kLockstepExternal;
  return c;
}

RealTimeNodeThread::RealTimeNodeThread(Node& node, const WallClock& clock, const std::string& lcm_url)
    : RealTimeNodeThread(node, ThreadClock::free_running(clock), lcm_url) {}

namespace {

const RealTimeClock* pick_clock(const ThreadClock& how, std::unique_ptr<SteppedClock>& stepped) {
  if (how.kind == ThreadClock::Kind::kWall) {
    if (how.wall == nullptr) throw std::invalid_argument("RealTimeNodeThread: a free-running thread needs a wall clock");
    return how.wall;
  }
  stepped = std::make_unique<SteppedClock>(0);
  return stepped.get();
}

}  // namespace

RealTimeNodeThread::RealTimeNodeThread(Node& node, const ThreadClock& how, const std::string& lcm_url)
    : node_(node), clock_(pick_clock(how, stepped_)), bus_(lcm_url, clock_) {
  const bool master = how.kind == ThreadClock::Kind::kLockstepMaster;
  const bool answers = master || (how.kind == ThreadClock::Kind::kLockstepFollower && how.acknowledges);
  // The master listens to its followers' answers, which they publish, on a bus of their own.
  if (answers) answers_bus_ = std::make_unique<LcmBus>(answers_lcm_url(bus_.url()), clock_);
  executor_ = std::make_unique<RealTimeExecutor>(*clock_, &bus_, master ? answers_bus_.get() : nullptr);
  executor_->set_deadline_miss_us(how.deadline_miss_us);
  if (master) {
    pacer_ = std::make_unique<LockstepPacer>(*stepped_, bus_, how.pacing);
    executor_->set_clock_driver(pacer_.get());
    LockstepPacer* pacer = pacer_.get();
    answers_bus_->subscribe<a3lcm::clock_ack_t>(channels::kClockAck, [pacer](const a3lcm::clock_ack_t& m, int64_t) {
      pacer->note_follower_ack(m.node, m.utime_us, m.round, m.messages_published);
    });
  } else if (how.kind == ThreadClock::Kind::kLockstepFollower) {
    SteppedClock* clock = stepped_.get();
    if (how.acknowledges) {
      acknowledger_ = std::make_unique<GrantAcknowledger>(*clock, bus_, *answers_bus_, node_.name());
      executor_->set_clock_driver(acknowledger_.get());
    }
    GrantAcknowledger* ack = acknowledger_.get();
    bus_.subscribe<a3lcm::sim_clock_t>(channels::kClock, [clock, ack](const a3lcm::sim_clock_t& m, int64_t) {
      clock->advance_to(m.utime_us);
      if (ack != nullptr) ack->grant_heard(m.round);
    });
  }
}

RealTimeNodeThread::~RealTimeNodeThread() { stop_and_join(); }

void RealTimeNodeThread::publish_stats(bool final) {
  NamedValues timing = executor_timing(*executor_);
  if (pacer_) {
    const NamedValues pacing = lockstep_timing(pacer_->stats());
    timing.insert(timing.end(), pacing.begin(), pacing.end());
  }
  bus_.publish(channels::kNodeStats, make_node_stats(node_.name(), clock_->now_us(), final, node_.counters(), timing));
}

void RealTimeNodeThread::start() {
  node_.start(*executor_, bus_for_node(node_, bus_, node_bus_));
  if (stats_period_s_ > 0.0) {
    executor_->set_housekeeping(static_cast<int64_t>(stats_period_s_ * 1e9), [this] { publish_stats(false); });
  }
  thread_ = std::thread([this] {
    try {
      executor_->run();
      publish_stats(true);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(failure_mutex_);
      failure_ = e.what();
      log_error(node_.name(), std::string("stopped: ") + e.what());
    }
  });
}

void RealTimeNodeThread::stop_and_join() {
  executor_->stop();
  if (thread_.joinable()) thread_.join();
}

std::string RealTimeNodeThread::failure() const {
  std::lock_guard<std::mutex> lock(failure_mutex_);
  return failure_;
}

}  // namespace a3::common
