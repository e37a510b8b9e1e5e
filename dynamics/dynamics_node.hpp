// The dynamics node: subscribes to rotor commands (A3_ACTUATORS, actuator_cmd_t), integrates the
// vehicle on a fixed publish grid (100 Hz by default) with the command held between steps, and
// publishes the true state (A3_STATE, vehicle_state_t) and crashes (A3_SAFETY). The same object
// runs in real time (its own thread or process) and in virtual time (the scheduler).
//
// Input checking, as an ESC would do it: a command with a NaN or infinite throttle is rejected
// (counted, logged); a throttle outside [0, 1] is clamped (counted, logged); with no command for
// longer than the timeout (0.5 s by default) the motors spin down; the node keeps publishing, and
// reports it once per silence as a safety event (kind "command_timeout"). The timeout counts
// simulated time: in lockstep (the default real-time mode) simulated time cannot pass without
// the flight controller's commands, so it trips only for a controller that is alive and
// silent; free-running (`--sync free`, a real controller), a late host can trip it too, and the
// episode's real-time accounting says whether the host was late.
// Until the first command arrives the rotors hold the initial state's speeds (for the timeout).
// Steps fall on a grid of whole periods of the clock (k · period), in both runtimes.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "a3lcm/actuator_cmd_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "common/node.hpp"
#include "dynamics/integrator.hpp"

namespace a3::dynamics {

struct DynamicsNodeConfig {
  VehicleParams params = default_vehicle_params();  // payloads included
  IntegratorKind integrator = IntegratorKind::kRk4;
  IntegratorOptions integrator_options;
  double publish_rate_hz = 100.0;
  double command_timeout_s = 0.5;
  VehicleState initial_state;  // at or below z = 0: on the ground
  Eigen::Vector3d mean_wind_W_mps = Eigen::Vector3d::Zero();
  TurbulenceParams turbulence;
  uint64_t seed = 1;
  common::VehicleId vehicle = 0;  // whose channels: A3_STATE, A3_ACTUATORS, A3_SAFETY (channel.hpp)
};

class DynamicsNode final : public common::Node {
 public:
  explicit DynamicsNode(DynamicsNodeConfig config);
  ~DynamicsNode() override;

  std::string name() const override { return "dynamics"; }
  void start(common::Executor& executor, common::Bus& bus) override;
  // Subscribes A3_ACTUATORS; publishes A3_STATE and A3_SAFETY (a crash).
  std::optional<common::NodePorts> ports() const override;

  // steps, commands, rejected (NaN or infinite throttle), clamped (throttle outside [0, 1]),
  // stale_steps (steps run with the motors spun down for lack of commands), integration_errors.
  const common::CounterSet& counters() const override { return counter_set_; }
  // Read only from the node's own thread (or after it stopped).
  const Integrator& integrator() const { return *integrator_; }
  const QuadrotorModel& model() const { return *model_; }

 private:
  void on_command(const a3lcm::actuator_cmd_t& cmd, int64_t recv_utime_us);
  void step();
  void publish_state(int64_t utime_us);
  void publish_events(int64_t utime_us);
  void publish_command_timeout(int64_t utime_us);
  void warn(uint64_t count, const std::string& message) const;

  DynamicsNodeConfig config_;
  std::unique_ptr<QuadrotorModel> model_;
  std::unique_ptr<WindField> wind_;
  std::unique_ptr<Integrator> integrator_;
  common::Executor* executor_ = nullptr;
  common::Bus* bus_ = nullptr;
  int64_t period_us_ = 10000;
  common::TypedChannel<a3lcm::vehicle_state_t> state_channel_;  // published every step: resolved once
  int64_t start_us_ = 0;
  uint64_t step_index_ = 0;
  RotorSpeeds command_radps_{};
  std::optional<int64_t> last_command_us_;
  bool was_stale_ = false;
  common::CounterSet counter_set_;
  struct Counters {
    explicit Counters(common::CounterSet& s)
        : steps(s.add("steps")), commands_received(s.add("commands")), commands_rejected(s.add("rejected")),
          commands_clamped(s.add("clamped")), stale_steps(s.add("stale_steps")),
          integration_errors(s.add("integration_errors")) {}
    common::Counter &steps, &commands_received, &commands_rejected, &commands_clamped, &stale_steps,
        &integration_errors;
  } counters_{counter_set_};
};

}  // namespace a3::dynamics
