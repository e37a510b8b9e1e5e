// A closed loop for testing the flight controller's logic without CAN: the dynamics model,
// the simulated sensors at their rates (IMU 250 Hz, GNSS 10 Hz, baro and magnetometer 50 Hz,
// battery 5 Hz) and the flight controller at 250 Hz, in one thread.
#pragma once

#include <functional>
#include <memory>

#include "bridge/fc/flight_controller.hpp"
#include "bridge/sim/sensor_model.hpp"
#include "dynamics/battery.hpp"
#include "dynamics/integrator.hpp"

namespace a3::test {

inline bridge::FcParams fc_params_for(const dynamics::VehicleParams& v) {
  bridge::FcParams p;
  p.vehicle.mass_kg = v.total_mass_kg();
  p.vehicle.arm_length_m = v.arm_length_m;
  p.vehicle.thrust_coeff_N_per_radps2 = v.rotor.thrust_coeff_N_per_radps2;
  p.vehicle.torque_coeff_Nm_per_radps2 = v.rotor.drag_torque_coeff_Nm_per_radps2;
  p.vehicle.max_rotor_speed_radps = v.rotor.max_speed_radps;
  p.vehicle.inertia_xx_kgm2 = v.inertia_xx_kgm2;
  p.vehicle.inertia_yy_kgm2 = v.inertia_yy_kgm2;
  p.vehicle.inertia_zz_kgm2 = v.inertia_zz_kgm2;
  return p;
}

class DirectLoop {
 public:
  static constexpr double kTick_s = 0.004;
  static constexpr double kHomeMsl_m = 488.0;

  // turbulence: Dryden gusts on top of mean_wind (off: a steady wind).
  DirectLoop(const dynamics::VehicleParams& vehicle, bridge::FcParams fc_params,
             const Eigen::Vector3d& mean_wind = Eigen::Vector3d::Zero(), uint64_t seed = 1, bool turbulence = true)
      : model_(vehicle),
        wind_(mean_wind, dynamics::TurbulenceParams{turbulence, 10.0, 0.05}, seed),
        integrator_(dynamics::make_integrator(dynamics::IntegratorKind::kCvode, model_, wind_)),
        fc_(std::move(fc_params)),
        sensors_(bridge::SensorNoise{}, seed) {
    integrator_->reset(dynamics::VehicleState{}, 0.0);
  }

  bridge::FlightController& fc() { return fc_; }
  const dynamics::Integrator& vehicle() const { return *integrator_; }
  dynamics::Integrator& vehicle_mut() { return *integrator_; }
  double time_s() const { return tick_ * kTick_s; }
  bridge::FlightCommandResult command(bridge::FlightCommand c) {
    c.seq = ++seq_;
    return fc_.on_command(c, time_s());
  }
  // Keeps the command link alive (as the bridge's heartbeats would) when heartbeats_ is on.
  bool heartbeats = true;
  double battery_offset_pct = 0.0;  // subtracted from the reading, to fake a drained battery

  // Runs to t_end_s; on_tick (if any) sees the time after each tick.
  void run_until(double t_end_s, const std::function<void(double)>& on_tick = {}) {
    while (time_s() < t_end_s - 1e-9) {
      const double t = time_s();
      const dynamics::VehicleState& s = integrator_->state();
      bridge::TruthSample truth;
      truth.t_s = t;
      truth.p_W_m = s.p_W_m;
      truth.v_W_mps = s.v_W_mps;
      truth.q_WB = s.q_WB;
      truth.w_B_radps = s.w_B_radps;
      const Eigen::Vector3d wind = wind_.wind_W_mps(t);
      truth.specific_force_B_mps2 = integrator_->on_ground()
                                        ? Eigen::Vector3d(s.q_WB.conjugate() * Eigen::Vector3d(0, 0, dynamics::kGravity_mps2))
                                        : model_.specific_force_B_mps2(s, wind);
      auto& est = fc_.estimator();
      est.on_imu(t, sensors_.gyro_B_radps(truth), sensors_.accel_B_mps2(truth));
      if (tick_ % 25 == 0) est.on_gnss(t, sensors_.gnss_position_W_m(truth), sensors_.gnss_velocity_W_mps(truth));
      if (tick_ % 5 == 0) {
        est.on_baro(t, bridge::isa_altitude_m(sensors_.static_pressure_Pa(truth, kHomeMsl_m)) - kHomeMsl_m);
        est.on_magnetometer(t, sensors_.magnetic_field_B_gauss(truth));
      }
      if (tick_ % 50 == 0) {
        const double power = model_.electrical_power_W(s.rotor_speed_radps);
        const auto b = dynamics::read_battery(model_.params().battery, model_.battery_energy_J(), s.energy_used_J, power);
        fc_.on_battery(t, b.percent - battery_offset_pct);
      }
      if (heartbeats && tick_ % 50 == 0) fc_.on_command(bridge::FlightCommand{}, t);
      const bridge::FcOutput out = fc_.step(t);
      dynamics::RotorSpeeds cmd{};
      for (int i = 0; i < 4; ++i) cmd[i] = out.armed ? out.throttle[i] * model_.params().rotor.max_speed_radps : 0.0;
      ++tick_;
      integrator_->advance_to(time_s(), cmd);
      if (on_tick) on_tick(time_s());
    }
  }

 private:
  dynamics::QuadrotorModel model_;
  dynamics::WindField wind_;
  std::unique_ptr<dynamics::Integrator> integrator_;
  bridge::FlightController fc_;
  bridge::SensorModel sensors_;
  int64_t tick_ = 0;
  int32_t seq_ = 0;
};

}  // namespace a3::test
