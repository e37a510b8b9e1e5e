// bridge/fc/fc_params.default.json holds exactly the code's defaults, and bridge/fc/README.md
// names every field of it: the documented defaults cannot drift from the ones in force.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "bridge/fc/fc_params.hpp"
#include "common/json_file.hpp"
#include "tests/test_support.hpp"

namespace a3::bridge {
namespace {

const std::filesystem::path kDefaults = a3::test::source_dir() / "bridge/fc/fc_params.default.json";

TEST(FcParamsFile, HoldsTheCodesDefaults) {
  const nlohmann::json file = common::load_json_file(kDefaults);
  // Start from values unlike every default: each field the file sets must come back as the default.
  FcParams odd;
  odd.vehicle = FcVehicle{9, 9, 9, 9, 9, 9, 9, 9};
  odd.gains = FcGains{9, 9, 9, 9, 9, 9, 9};
  odd.limits = FcLimits{99, 99, 99, 99, 79, 99, 99, 99, 99, 99, 99};
  odd.failsafe = FcFailsafeParams{99, 99, 99, 98, 99, 99};
  odd.control_rate_hz = 999;
  odd.status_rate_hz = 99;
  const FcParams p = fc_params_from_json(file, kDefaults.string(), odd);
  const FcParams d;
  EXPECT_EQ(p.vehicle.mass_kg, d.vehicle.mass_kg);
  EXPECT_EQ(p.vehicle.arm_length_m, d.vehicle.arm_length_m);
  EXPECT_EQ(p.vehicle.thrust_coeff_N_per_radps2, d.vehicle.thrust_coeff_N_per_radps2);
  EXPECT_EQ(p.vehicle.torque_coeff_Nm_per_radps2, d.vehicle.torque_coeff_Nm_per_radps2);
  EXPECT_EQ(p.vehicle.max_rotor_speed_radps, d.vehicle.max_rotor_speed_radps);
  EXPECT_EQ(p.vehicle.inertia_xx_kgm2, d.vehicle.inertia_xx_kgm2);
  EXPECT_EQ(p.vehicle.inertia_yy_kgm2, d.vehicle.inertia_yy_kgm2);
  EXPECT_EQ(p.vehicle.inertia_zz_kgm2, d.vehicle.inertia_zz_kgm2);
  EXPECT_EQ(p.gains.position_p, d.gains.position_p);
  EXPECT_EQ(p.gains.velocity_p, d.gains.velocity_p);
  EXPECT_EQ(p.gains.velocity_i, d.gains.velocity_i);
  EXPECT_EQ(p.gains.attitude_p, d.gains.attitude_p);
  EXPECT_EQ(p.gains.yaw_p, d.gains.yaw_p);
  EXPECT_EQ(p.gains.rate_p, d.gains.rate_p);
  EXPECT_EQ(p.gains.rate_i, d.gains.rate_i);
  EXPECT_EQ(p.limits.max_horizontal_speed_mps, d.limits.max_horizontal_speed_mps);
  EXPECT_EQ(p.limits.max_climb_speed_mps, d.limits.max_climb_speed_mps);
  EXPECT_EQ(p.limits.max_descent_speed_mps, d.limits.max_descent_speed_mps);
  EXPECT_EQ(p.limits.max_horizontal_accel_mps2, d.limits.max_horizontal_accel_mps2);
  EXPECT_EQ(p.limits.max_tilt_deg, d.limits.max_tilt_deg);
  EXPECT_EQ(p.limits.max_rate_radps, d.limits.max_rate_radps);
  EXPECT_EQ(p.limits.max_yaw_rate_radps, d.limits.max_yaw_rate_radps);
  EXPECT_EQ(p.limits.takeoff_speed_mps, d.limits.takeoff_speed_mps);
  EXPECT_EQ(p.limits.land_speed_mps, d.limits.land_speed_mps);
  EXPECT_EQ(p.limits.brake_accel_mps2, d.limits.brake_accel_mps2);
  EXPECT_EQ(p.limits.default_speed_mps, d.limits.default_speed_mps);
  EXPECT_EQ(p.failsafe.link_loss_hold_s, d.failsafe.link_loss_hold_s);
  EXPECT_EQ(p.failsafe.link_loss_return_s, d.failsafe.link_loss_return_s);
  EXPECT_EQ(p.failsafe.low_battery_return_pct, d.failsafe.low_battery_return_pct);
  EXPECT_EQ(p.failsafe.low_battery_land_pct, d.failsafe.low_battery_land_pct);
  EXPECT_EQ(p.failsafe.fence_margin_m, d.failsafe.fence_margin_m);
  EXPECT_EQ(p.failsafe.return_altitude_m, d.failsafe.return_altitude_m);
  EXPECT_EQ(p.control_rate_hz, d.control_rate_hz);
  EXPECT_EQ(p.status_rate_hz, d.status_rate_hz);
}

TEST(FcParamsFile, TheReadmeDocumentsEveryField) {
  std::ifstream in(a3::test::source_dir() / "bridge/fc/README.md");
  ASSERT_TRUE(in) << "bridge/fc/README.md missing";
  std::stringstream text;
  text << in.rdbuf();
  const std::string readme = text.str();
  const nlohmann::json file = common::load_json_file(kDefaults);
  for (const auto& [key, value] : file.items()) {
    if (value.is_object()) {
      EXPECT_NE(readme.find("`" + key + "`"), std::string::npos) << "section " << key;
      for (const auto& [field, v] : value.items()) {
        EXPECT_NE(readme.find("`" + field + "`"), std::string::npos) << key << "/" << field;
      }
    } else {
      EXPECT_NE(readme.find("`" + key + "`"), std::string::npos) << key;
    }
  }
}

TEST(FcParamsFile, BadValuesAreErrorsNamingTheirPath) {
  try {
    fc_params_from_json(nlohmann::json::parse(R"({"gains": {"rate_p": -1}})"), "fc.json");
    FAIL() << "accepted a negative gain";
  } catch (const common::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fc.json/gains/rate_p"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fc_params_from_json(nlohmann::json::parse(R"({"control_rate_hz": 100})"), "fc.json"),
               common::InputError);
}

}  // namespace
}  // namespace a3::bridge
