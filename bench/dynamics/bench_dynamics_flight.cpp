// The plotted flight: take-off from the ground, climb to 20 m, legs east and north with yaw
// turns and a climb, back home, descent and a gentle landing (flight_controller.hpp's
// demo_plan), flown by the controller node against the dynamics node (RK4 by default) in virtual time,
// in a 5 m/s wind from 240° with Dryden turbulence. Writes one CSV row per published state
// (10 ms) for plot_flight.gp and prints a summary (touchdown speed, battery used, events).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>

#include "bench/dynamics/bus_recorder.hpp"
#include "bench/dynamics/flight_controller.hpp"
#include "common/runtime.hpp"
#include "dynamics/dynamics_node.hpp"

int main(int argc, char** argv) {
  using namespace a3;
  using namespace a3::bench;
  CLI::App app("Fly the demonstration flight in virtual time and write its trajectory as CSV.");
  std::string out_csv = "dynamics_flight.csv";
  std::string integrator = "rk4";
  double wind_mps = 5.0, wind_dir_deg = 240.0;
  uint64_t seed = 3;
  app.add_option("--csv", out_csv, "output CSV (default dynamics_flight.csv)");
  app.add_option("--integrator", integrator, "rk4 (default), cvode or ode")->check(CLI::IsMember(dynamics::integrator_names()));
  app.add_option("--wind-mps", wind_mps, "mean wind speed (default 5)")->check(CLI::NonNegativeNumber);
  app.add_option("--wind-dir-deg", wind_dir_deg, "direction the wind blows from (default 240)");
  app.add_option("--seed", seed, "turbulence seed (default 3)");
  CLI11_PARSE(app, argc, argv);

  dynamics::DynamicsNodeConfig config;
  config.integrator = dynamics::parse_integrator_kind(integrator);
  config.mean_wind_W_mps = dynamics::wind_from_report(wind_mps, wind_dir_deg);
  config.seed = seed;  // on the ground at the origin, rotors stopped
  const FlightPlan plan = demo_plan();
  const double end_s = plan.end_s() + 4.0;

  common::VirtualRuntime rt;
  dynamics::DynamicsNode dyn(config);
  FlightControllerNode controller(config.params, plan);
  BusRecorder recorder(true);
  rt.add(recorder);
  rt.add(dyn);
  rt.add(controller);
  rt.run_until(static_cast<int64_t>(end_s * 1e6));

  std::ofstream out(out_csv);
  if (!out) {
    std::cerr << "cannot write " << out_csv << "\n";
    return 1;
  }
  out << std::fixed << std::setprecision(4);
  out << "t_s,x_m,y_m,z_m,x_ref_m,y_ref_m,z_ref_m,roll_deg,pitch_deg,yaw_deg,yaw_ref_deg,w0_radps,w1_radps,"
         "w2_radps,w3_radps,battery_pct,battery_v,power_w,speed_mps,on_ground,wind_x_mps,wind_y_mps\n";
  double touchdown_speed = 0.0, max_speed = 0.0, max_tilt_deg = 0.0;
  bool was_on_ground = true;
  double prev_vz = 0.0;
  double yaw_unwrapped = 0.0, prev_yaw = 0.0;  // continuous through ±180° for the plot
  for (const auto& s : recorder.states()) {
    const double t = s.utime_us * 1e-6;
    const Reference ref = plan.at(t);
    const Eigen::Quaterniond q(s.q_WB[0], s.q_WB[1], s.q_WB[2], s.q_WB[3]);
    const Eigen::Vector3d rpy = dynamics::roll_pitch_yaw_rad(q) * 180.0 / M_PI;
    const double speed = std::sqrt(s.v_W_mps[0] * s.v_W_mps[0] + s.v_W_mps[1] * s.v_W_mps[1] + s.v_W_mps[2] * s.v_W_mps[2]);
    yaw_unwrapped += std::remainder(rpy.z() - prev_yaw, 360.0);
    prev_yaw = rpy.z();
    out << t << ',' << s.p_W_m[0] << ',' << s.p_W_m[1] << ',' << s.p_W_m[2] << ',' << ref.p_W_m.x() << ','
        << ref.p_W_m.y() << ',' << std::max(0.0, ref.p_W_m.z()) << ',' << rpy.x() << ',' << rpy.y() << ',' << yaw_unwrapped
        << ',' << ref.yaw_rad * 180.0 / M_PI;
    for (double w : s.rotor_speed_radps) out << ',' << w;
    out << ',' << s.battery_pct << ',' << s.battery_voltage_v << ',' << s.power_w << ',' << speed << ','
        << (s.on_ground ? 1 : 0) << ',' << s.wind_W_mps[0] << ',' << s.wind_W_mps[1] << '\n';
    if (s.on_ground && !was_on_ground && t > 10.0) touchdown_speed = -prev_vz;
    was_on_ground = s.on_ground;
    prev_vz = s.v_W_mps[2];
    max_speed = std::max(max_speed, speed);
    max_tilt_deg = std::max(max_tilt_deg, std::acos(std::clamp(1.0 - 2.0 * (q.x() * q.x() + q.y() * q.y()), -1.0, 1.0)) * 180.0 / M_PI);
  }
  const auto& last = recorder.states().back();
  std::printf("flight: %.0f s, %zu states; max speed %.1f m/s, max tilt %.1f deg; touchdown at %.2f m/s; "
              "landed at (%.2f, %.2f) m, crashed %s; battery %.1f %% left\n",
              end_s, recorder.states().size(), max_speed, max_tilt_deg, touchdown_speed, last.p_W_m[0],
              last.p_W_m[1], last.crashed ? "yes" : "no", last.battery_pct);
  std::printf("wrote %s\n", out_csv.c_str());
  return last.crashed || !last.on_ground ? 1 : 0;
}
