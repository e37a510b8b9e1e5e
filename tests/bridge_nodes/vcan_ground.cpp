// The ground side of the real-vcan closed-loop test (scripts/vcan-vm/closed-loop-test.sh): over
// LCM, as the tool server would, it sends heartbeats at 5 Hz and a short mission (take off to
// 5 m, hold, go 10 m east, land) to the bridge, and checks what A3_STATE and A3_FC_STATUS say
// at each step. Prints one line per step and a summary; exits 0 when the mission went as it
// should, 1 when it did not, 77 when LCM cannot run here.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "a3lcm/fc_command_t.hpp"
#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/channels.hpp"
#include "common/runtime.hpp"

namespace {

using a3lcm::fc_command_t;
using a3lcm::fc_status_t;
using a3lcm::vehicle_state_t;

class Ground final : public a3::common::Node {
 public:
  std::string name() const override { return "ground"; }
  void start(a3::common::Executor& executor, a3::common::Bus& bus) override {
    executor_ = &executor;
    bus_ = &bus;
    bus.subscribe<fc_status_t>(a3::common::channels::kFcStatus.of(0), [this](const fc_status_t& s, int64_t) {
      std::lock_guard<std::mutex> lock(mutex_);
      status_ = s;
      ++statuses_;
    });
    bus.subscribe<vehicle_state_t>(a3::common::channels::kState.of(0), [this](const vehicle_state_t& s, int64_t) {
      std::lock_guard<std::mutex> lock(mutex_);
      state_ = s;
      ++states_;
      if (sampling_) {
        z_error_sum_ += (s.p_W_m[2] - z_target_) * (s.p_W_m[2] - z_target_);
        ++z_samples_;
      }
    });
    executor.schedule_every(200'000, [this] { send(fc_command_t::HEARTBEAT, seq_); });
  }
  // Thread-safe: LCM publication is.
  int32_t command(int8_t kind, double x, double y, double z, double speed = 0.0) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++seq_;
    send_locked(kind, seq_, x, y, z, speed);
    return seq_;
  }
  template <class F>
  auto read(F f) {
    std::lock_guard<std::mutex> lock(mutex_);
    return f(status_, state_, statuses_, states_);
  }
  void sample_altitude(bool on, double target) {
    std::lock_guard<std::mutex> lock(mutex_);
    sampling_ = on;
    z_target_ = target;
  }
  double altitude_rms_m() {
    std::lock_guard<std::mutex> lock(mutex_);
    return z_samples_ > 0 ? std::sqrt(z_error_sum_ / z_samples_) : -1.0;
  }

 private:
  void send(int8_t kind, int32_t seq) {
    std::lock_guard<std::mutex> lock(mutex_);
    send_locked(kind, seq, 0, 0, 0, 0);
  }
  void send_locked(int8_t kind, int32_t seq, double x, double y, double z, double speed) {
    fc_command_t c{};
    c.utime_us = executor_->clock().now_us();
    c.seq = seq;
    c.command = kind;
    c.target_W_m[0] = x;
    c.target_W_m[1] = y;
    c.target_W_m[2] = z;
    c.speed_limit_mps = speed;
    c.yaw_deg = std::nan("");
    bus_->publish(a3::common::channels::kFcCommand.of(0), c);
  }

  a3::common::Executor* executor_ = nullptr;
  a3::common::Bus* bus_ = nullptr;
  std::mutex mutex_;
  fc_status_t status_{};
  vehicle_state_t state_{};
  uint64_t statuses_ = 0, states_ = 0;
  int32_t seq_ = 0;
  bool sampling_ = false;
  double z_target_ = 0.0, z_error_sum_ = 0.0;
  uint64_t z_samples_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ground station of the real-vcan closed-loop test"};
  std::string lcm_url;
  double rtf = 1.0;
  app.add_option("--lcm-url", lcm_url, "LCM URL");
  app.add_option("--rtf", rtf, "real-time factor of the rig");
  CLI11_PARSE(app, argc, argv);

  const a3::common::WallClock clock(rtf);
  Ground ground;
  std::unique_ptr<a3::common::RealTimeNodeThread> thread;
  try {
    thread = std::make_unique<a3::common::RealTimeNodeThread>(ground, clock, lcm_url);
    thread->bus().check_loopback();
  } catch (const std::exception& e) {
    std::printf("ground: LCM cannot run here: %s\n", e.what());
    return 77;
  }
  thread->start();
  const int64_t wall0_ns = a3::common::WallClock::monotonic_now_ns();
  bool ok = true;
  // Waits (polling every 20 ms of wall time) until pred holds or sim timeout_s passes.
  const auto wait_for = [&](const char* what, double timeout_s, const std::function<bool(const fc_status_t&, const vehicle_state_t&, uint64_t)>& pred) {
    const double t_end = clock.now_s() + timeout_s;
    while (clock.now_s() < t_end) {
      if (ground.read([&](const fc_status_t& s, const vehicle_state_t& v, uint64_t ns, uint64_t nv) {
            return ns > 5 && nv > 50 && pred(s, v, ns);
          })) {
        ground.read([&](const fc_status_t& s, const vehicle_state_t& v, uint64_t, uint64_t) {
          std::printf("ground: t=%6.2f s  %-34s ok: mode %d armed %d failsafe %d  true p=(%.2f, %.2f, %.2f)\n",
                      clock.now_s(), what, s.mode, s.armed, s.failsafe, v.p_W_m[0], v.p_W_m[1], v.p_W_m[2]);
          return 0;
        });
        return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ground.read([&](const fc_status_t& s, const vehicle_state_t& v, uint64_t ns, uint64_t nv) {
      std::printf("ground: t=%6.2f s  %-34s FAILED after %.0f s: mode %d armed %d failsafe %d reason '%s' "
                  "true p=(%.2f, %.2f, %.2f); %llu statuses, %llu states\n",
                  clock.now_s(), what, timeout_s, s.mode, s.armed, s.failsafe, s.last_command_reason.c_str(),
                  v.p_W_m[0], v.p_W_m[1], v.p_W_m[2], static_cast<unsigned long long>(ns),
                  static_cast<unsigned long long>(nv));
      return 0;
    });
    ok = false;
    return false;
  };

  // Statuses (from the fc through the bridge) and states (from the dynamics) are flowing.
  const auto live = [](const fc_status_t&, const vehicle_state_t&, uint64_t) { return true; };
  if (wait_for("dynamics, bridge and fc alive", 30.0, live)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(1000 / rtf)));  // estimator settles
    const int32_t takeoff = ground.command(fc_command_t::TAKEOFF, 0, 0, 5.0);
    if (wait_for("take-off accepted", 2.0, [&](const fc_status_t& s, const vehicle_state_t&, uint64_t) {
          return s.last_command_seq == takeoff && s.last_command_accepted;
        }) &&
        wait_for("reached 5 m and holds", 15.0, [](const fc_status_t& s, const vehicle_state_t& v, uint64_t) {
          return s.mode == fc_status_t::HOLD && std::abs(v.p_W_m[2] - 5.0) < 0.5;
        })) {
      ground.sample_altitude(true, 5.0);
      std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(3000 / rtf)));
      ground.sample_altitude(false, 5.0);
      const double rms = ground.altitude_rms_m();
      std::printf("ground: hold at 5 m for 3 s: altitude RMS error %.3f m\n", rms);
      if (!(rms >= 0.0 && rms < 0.3)) ok = false;
      ground.command(fc_command_t::GOTO, 10.0, 0.0, 5.0, 4.0);
      if (wait_for("went 10 m east and holds", 15.0, [](const fc_status_t& s, const vehicle_state_t& v, uint64_t) {
            return s.mode == fc_status_t::HOLD && std::abs(v.p_W_m[0] - 10.0) < 0.5;
          })) {
        ground.command(fc_command_t::LAND, 0, 0, 0);
        wait_for("landed and disarmed", 25.0, [](const fc_status_t& s, const vehicle_state_t& v, uint64_t) {
          return s.mode == fc_status_t::DISARMED && !s.armed && v.on_ground && !v.crashed;
        });
      }
    }
  }
  const double wall_s = (a3::common::WallClock::monotonic_now_ns() - wall0_ns) * 1e-9;
  ground.read([&](const fc_status_t&, const vehicle_state_t&, uint64_t ns, uint64_t nv) {
    std::printf("ground: %s: %.1f s simulated in %.1f s of wall time (real-time factor %g); %llu states (%.0f/s), "
                "%llu statuses (%.1f/s) received\n",
                ok ? "mission completed" : "MISSION FAILED", clock.now_s(), wall_s, rtf,
                static_cast<unsigned long long>(nv), nv / clock.now_s(), static_cast<unsigned long long>(ns),
                ns / clock.now_s());
    return 0;
  });
  thread->stop_and_join();
  return ok ? 0 : 1;
}
