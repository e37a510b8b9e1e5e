// The model's parts on their own: airframe files and their errors, payloads, wind and
// turbulence statistics, the battery, and set-up from an α³-Bench initial_state.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <fstream>

#include "common/json_file.hpp"
#include "dynamics/battery.hpp"
#include "dynamics/quadrotor_model.hpp"
#include "dynamics/scenario_setup.hpp"
#include "dynamics/wind_field.hpp"
#include "tests/test_support.hpp"

namespace a3::dynamics {
namespace {

using nlohmann::json;

json iris_json() {
  std::ifstream in(std::string(A3_SOURCE_DIR) + "/dynamics/airframes/iris.json");
  return json::parse(in);
}

std::string error_of(const json& j) {
  try {
    vehicle_params_from_json(j, "test.json");
  } catch (const common::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(VehicleParams, BuiltInAirframesLoadAndAreWhatTheFilesSay) {
  const VehicleParams iris = default_vehicle_params();
  EXPECT_DOUBLE_EQ(iris.mass_kg, 1.5);
  EXPECT_DOUBLE_EQ(iris.rotor.thrust_coeff_N_per_radps2, 5.84e-6);
  EXPECT_DOUBLE_EQ(iris.inertia_zz_kgm2, 0.055225);
  EXPECT_EQ(iris.battery.cells, 3);
  const VehicleParams heavy = airframe_by_name_or_path("heavy-lift");
  EXPECT_DOUBLE_EQ(heavy.mass_kg, 6.3);
  // Thrust-to-weight: the Iris about 1.9, the heavy-lift 2 at its 9 kg maximum take-off mass.
  const double iris_tw = 4 * iris.rotor.thrust_coeff_N_per_radps2 * std::pow(iris.rotor.max_speed_radps, 2) / (iris.mass_kg * kGravity_mps2);
  const double heavy_tw = 4 * heavy.rotor.thrust_coeff_N_per_radps2 * std::pow(heavy.rotor.max_speed_radps, 2) / (9.0 * kGravity_mps2);
  EXPECT_NEAR(iris_tw, 1.92, 0.02);
  EXPECT_NEAR(heavy_tw, 2.0, 0.02);
  // Endurance in hover, from the power model: Iris ~20 min, heavy-lift ~50 min.
  const QuadrotorModel m_iris(iris), m_heavy(heavy);
  const RotorSpeeds hi{m_iris.hover_speed_radps(), m_iris.hover_speed_radps(), m_iris.hover_speed_radps(), m_iris.hover_speed_radps()};
  const RotorSpeeds hh{m_heavy.hover_speed_radps(), m_heavy.hover_speed_radps(), m_heavy.hover_speed_radps(), m_heavy.hover_speed_radps()};
  EXPECT_NEAR(m_iris.battery_energy_J() / m_iris.electrical_power_W(hi) / 60.0, 20.0, 3.0);
  EXPECT_NEAR(m_heavy.battery_energy_J() / m_heavy.electrical_power_W(hh) / 60.0, 50.0, 6.0);
}

TEST(VehicleParams, BadAirframesAreRefusedWithFileAndPath) {
  json j = iris_json();
  j["rotor"]["max_speed_radps"] = "fast";
  EXPECT_NE(error_of(j).find("test.json/rotor/max_speed_radps: expected a number, got string"), std::string::npos) << error_of(j);
  j = iris_json();
  j.erase("mass_kg");
  EXPECT_NE(error_of(j).find("test.json/mass_kg: missing"), std::string::npos) << error_of(j);
  j = iris_json();
  j["inertia_kgm2"]["zz"] = -1;
  EXPECT_NE(error_of(j).find("test.json/inertia_kgm2/zz: must be > 0"), std::string::npos) << error_of(j);
  j = iris_json();
  j["battery"]["cells"] = 3.5;
  EXPECT_NE(error_of(j).find("test.json/battery/cells"), std::string::npos) << error_of(j);
  j = iris_json();
  j["battery"]["cell_empty_V"] = 4.3;
  EXPECT_NE(error_of(j).find("empty < nominal < full"), std::string::npos) << error_of(j);
  j = iris_json();
  j["rotor"]["figure_of_merit"] = 1.5;
  EXPECT_NE(error_of(j).find("figure_of_merit"), std::string::npos) << error_of(j);
  EXPECT_NE(error_of(json::array()).find("must be a JSON object"), std::string::npos);
  try {
    airframe_by_name_or_path("no-such-airframe");
    FAIL();
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("iris, heavy-lift"), std::string::npos) << e.what();
  }
}

TEST(VehicleParams, PayloadsAddMassDragPowerAndInertia) {
  const std::vector<Payload> payloads = {{"cam", 3.2, 0.01, 45.0}, {"ir", 1.8, 0.005, 30.0}};
  const VehicleParams base = airframe_by_name_or_path("heavy-lift");
  const VehicleParams p = with_payloads(base, payloads);
  EXPECT_DOUBLE_EQ(p.total_mass_kg(), 6.3 + 5.0);
  EXPECT_DOUBLE_EQ(p.payload_power_W, 75.0);
  EXPECT_DOUBLE_EQ(p.aero.drag_cdA_m2, base.aero.drag_cdA_m2 + 0.015);
  EXPECT_DOUBLE_EQ(p.inertia_xx_kgm2, base.inertia_xx_kgm2 + 5.0 * 0.01);
  EXPECT_DOUBLE_EQ(p.inertia_zz_kgm2, base.inertia_zz_kgm2);
  EXPECT_LT(QuadrotorModel(p).hover_throttle(), 1.0);  // the heavy-lift carries it
  EXPECT_GT(QuadrotorModel(with_payloads(default_vehicle_params(), p.payloads)).hover_throttle(), 1.0);  // an Iris cannot
}

TEST(Wind, MeteorologicalDirectionIsWhereTheWindComesFrom) {
  const Eigen::Vector3d from_north = wind_from_report(10.0, 0.0);
  EXPECT_NEAR(from_north.x(), 0.0, 1e-12);
  EXPECT_NEAR(from_north.y(), -10.0, 1e-12);  // blowing south
  const Eigen::Vector3d from_west = wind_from_report(5.0, 270.0);
  EXPECT_NEAR(from_west.x(), 5.0, 1e-12);  // blowing east
  EXPECT_NEAR(from_west.y(), 0.0, 1e-12);
}

TEST(Wind, TurbulenceHasTheDrydenIntensitiesAndIsReproducible) {
  const Eigen::Vector3d mean = wind_from_report(8.0, 240.0);
  TurbulenceParams t;
  t.reference_altitude_m = 50.0;
  WindField a(mean, t, 42), b(mean, t, 42), c(mean, t, 43);
  // h = 164 ft: σ_w = 0.8 m/s, σ_u = σ_w / (0.177 + 0.000823 h)^0.4
  const double h_ft = 50.0 * 3.28084;
  EXPECT_NEAR(a.sigma_mps().z(), 0.8, 1e-12);
  EXPECT_NEAR(a.sigma_mps().x(), 0.8 / std::pow(0.177 + 0.000823 * h_ft, 0.4), 1e-12);
  EXPECT_NE(a.wind_W_mps(0.3), c.wind_W_mps(0.3));
  // Continuous in time (interpolated).
  EXPECT_LT((a.wind_W_mps(10.0) - a.wind_W_mps(10.001)).norm(), 0.01);
  // Sample a long run: means and standard deviations per axis.
  const Eigen::Vector3d along = mean.normalized();
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(along);
  double s_u = 0, s_v = 0, s_w = 0, ss_u = 0, ss_v = 0, ss_w = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double time = 11.0 + i * 0.5;
    const Eigen::Vector3d g = a.wind_W_mps(time) - mean;
    EXPECT_EQ(a.wind_W_mps(time), b.wind_W_mps(time));
    const double u = g.dot(along), v = g.dot(across), w = g.z();
    s_u += u; s_v += v; s_w += w;
    ss_u += u * u; ss_v += v * v; ss_w += w * w;
  }
  EXPECT_NEAR(s_u / n, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(ss_u / n), a.sigma_mps().x(), 0.05 * a.sigma_mps().x());
  EXPECT_NEAR(std::sqrt(ss_v / n), a.sigma_mps().y(), 0.05 * a.sigma_mps().y());
  EXPECT_NEAR(std::sqrt(ss_w / n), a.sigma_mps().z(), 0.05 * a.sigma_mps().z());
  // Calm air has no turbulence.
  WindField calm(Eigen::Vector3d::Zero(), t, 1);
  EXPECT_EQ(calm.wind_W_mps(12.3), Eigen::Vector3d::Zero());
  TurbulenceParams off;
  off.enabled = false;
  WindField steady(mean, off, 1);
  EXPECT_EQ(steady.wind_W_mps(5.0), mean);
}

TEST(Battery, ChargeAndVoltage) {
  const BatteryParams b = default_vehicle_params().battery;
  const double capacity_J = 5.1 * 3600 * 3 * 3.7;
  BatteryReading r = read_battery(b, capacity_J, 0.0, 0.0);
  EXPECT_DOUBLE_EQ(r.percent, 100.0);
  EXPECT_NEAR(r.voltage_V, 12.6, 1e-9);  // 3 × 4.2 V open circuit
  r = read_battery(b, capacity_J, capacity_J / 2, 170.0);
  EXPECT_DOUBLE_EQ(r.percent, 50.0);
  const double ocv = 3 * 3.75;
  EXPECT_NEAR(r.voltage_V * r.current_A, 170.0, 1e-6);  // P = V I
  EXPECT_NEAR(r.voltage_V, ocv - r.current_A * 0.015, 1e-9);
  EXPECT_LT(r.voltage_V, ocv);
  r = read_battery(b, capacity_J, capacity_J * 1.1, 0.0);
  EXPECT_DOUBLE_EQ(r.percent, 0.0);
  EXPECT_TRUE(r.empty);
}

TEST(ScenarioSetup, AFlightStartSetsWindPayloadsPoseAndBattery) {
  FlightStart start;
  start.p_W_m = {100.0, 100.0, 300.0};
  start.yaw_deg = 90.0;
  start.wind_mps = 7.5;
  start.wind_dir_deg = 240.0;
  Payload a, b;
  a.mass_kg = 3.2;
  b.mass_kg = 1.8;
  start.payloads = {a, b};
  start.battery_pct = 60.0;
  DynamicsNodeConfig config;
  config.params = airframe_by_name_or_path("heavy-lift");
  apply_flight_start(start, false, config);
  EXPECT_NEAR(config.mean_wind_W_mps.norm(), 7.5, 1e-9);
  EXPECT_NEAR(config.mean_wind_W_mps.x(), 7.5 * std::sin(60 * M_PI / 180), 1e-9);  // toward 60°
  EXPECT_DOUBLE_EQ(config.params.total_mass_kg(), 6.3 + 5.0);
  EXPECT_DOUBLE_EQ(config.initial_state.p_W_m.z(), 300.0);
  EXPECT_NEAR(roll_pitch_yaw_rad(config.initial_state.q_WB).z(), M_PI / 2, 1e-12);
  EXPECT_GT(config.initial_state.rotor_speed_radps[0], 0.0);
  // 60 % charge: 40 % of the pack already drawn.
  const QuadrotorModel model(config.params);
  EXPECT_NEAR(config.initial_state.energy_used_J, 0.4 * model.battery_energy_J(), 1e-6);
  EXPECT_NEAR(read_battery(config.params.battery, model.battery_energy_J(), config.initial_state.energy_used_J, 0.0).percent,
              60.0, 1e-9);

  DynamicsNodeConfig ground;
  apply_flight_start(start, true, ground);
  EXPECT_DOUBLE_EQ(ground.initial_state.p_W_m.z(), 0.0);
  EXPECT_DOUBLE_EQ(ground.initial_state.rotor_speed_radps[0], 0.0);

  for (const double bad_pct : {0.0, -5.0, 100.5}) {
    FlightStart bad = start;
    bad.battery_pct = bad_pct;
    EXPECT_THROW(apply_flight_start(bad, true, config), std::invalid_argument) << bad_pct;
  }
  FlightStart storm = start;
  storm.wind_mps = std::numeric_limits<double>::infinity();
  EXPECT_THROW(apply_flight_start(storm, true, config), std::invalid_argument);
}

// derivatives() inlines its parts (one state copy, the rotor speeds clamped in place): each
// component must stay bit for bit what the public parts give, the lag seeing the raw rotor speed.
TEST(QuadrotorModel, DerivativesAreThePublicPartsBitForBit) {
  const QuadrotorModel model(default_vehicle_params());
  VehicleState s;
  s.p_W_m = {1.0, -2.0, 30.0};
  s.v_W_mps = {3.0, -1.0, 0.5};
  s.q_WB = Eigen::Quaterniond(0.9, 0.1, -0.2, 0.3);  // not unit: the model normalises
  s.w_B_radps = {0.3, -0.2, 0.1};
  s.rotor_speed_radps = {400.0, -5.0, 650.0, 0.0};  // a negative speed is clamped to 0
  s.energy_used_J = 1000.0;
  const RotorSpeeds command = {500.0, 100.0, 600.0, 0.0};
  const Eigen::Vector3d wind(2.0, -1.0, 0.5);
  double y[kStateSize], dydt[kStateSize];
  pack_state(s, y);
  model.derivatives(y, command, wind, false, dydt);

  VehicleState clean = s;
  for (double& w : clean.rotor_speed_radps) w = std::max(0.0, w);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(dydt[index::kRotor + i], model.rotor_acceleration_radps2(s.rotor_speed_radps[i], command[i])) << i;
  }
  EXPECT_NE(dydt[index::kRotor + 1], model.rotor_acceleration_radps2(0.0, command[1]));
  EXPECT_EQ(dydt[index::kEnergy], model.electrical_power_W(clean.rotor_speed_radps));
  const Wrench wrench = model.wrench(clean, wind);
  const Eigen::Vector3d a_W = wrench.force_W_N / model.mass_kg();
  const VehicleParams& p = model.params();
  const Eigen::Vector3d inertia(p.inertia_xx_kgm2, p.inertia_yy_kgm2, p.inertia_zz_kgm2);
  const Eigen::Vector3d& om = s.w_B_radps;
  const Eigen::Vector3d dw = (wrench.torque_B_Nm - om.cross(inertia.cwiseProduct(om))).cwiseQuotient(inertia);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(dydt[index::kP + i], s.v_W_mps[i]) << i;
    EXPECT_EQ(dydt[index::kV + i], a_W[i]) << i;
    EXPECT_EQ(dydt[index::kW + i], dw[i]) << i;
  }
}

}  // namespace
}  // namespace a3::dynamics
