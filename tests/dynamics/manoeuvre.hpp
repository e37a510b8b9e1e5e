// A scripted open-loop manoeuvre for tests: throttle offsets around hover that pitch, roll and
// yaw the vehicle, climb and level off, well away from the ground.
#pragma once

#include <array>

#include "dynamics/quadrotor_model.hpp"

namespace a3::test {

// Rotor speed commands (rad/s) at time t_s.
inline dynamics::RotorSpeeds manoeuvre_command(const dynamics::QuadrotorModel& model, double t_s) {
  const double hover = model.hover_speed_radps();
  double collective = 1.0, pitch = 0.0, roll = 0.0, yaw = 0.0;
  if (t_s >= 1.0 && t_s < 1.25) pitch = +0.02;   // rear rotors faster: nose down
  if (t_s >= 1.25 && t_s < 1.5) pitch = -0.02;
  if (t_s >= 2.0 && t_s < 8.0) collective = 1.03;  // climb
  if (t_s >= 3.0 && t_s < 3.5) yaw = +0.05;        // CW rotors faster: yaw left
  if (t_s >= 3.5 && t_s < 4.0) yaw = -0.05;
  if (t_s >= 5.0 && t_s < 5.2) roll = +0.02;       // right rotors faster: roll left
  if (t_s >= 5.2 && t_s < 5.4) roll = -0.02;
  if (t_s >= 6.0 && t_s < 6.25) pitch = -0.015;
  if (t_s >= 6.25 && t_s < 6.5) pitch = +0.015;
  // Rotors: 0 front-right CCW, 1 rear-left CCW, 2 front-left CW, 3 rear-right CW.
  const std::array<double, 4> front = {1, -1, 1, -1};
  const std::array<double, 4> right = {1, -1, -1, 1};
  const std::array<double, 4> cw = {-1, -1, 1, 1};
  dynamics::RotorSpeeds out;
  for (int i = 0; i < 4; ++i) {
    out[i] = hover * (collective - pitch * front[i] + roll * right[i] + yaw * cw[i]);
  }
  return out;
}

}  // namespace a3::test
