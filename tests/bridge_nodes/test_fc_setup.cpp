// rigs/run/fc_setup.hpp: the fc told the airframe the dynamics fly (payloads included), the
// geofence of a parsed initial_state, the home point.
#include <gtest/gtest.h>

#include "dynamics/vehicle_params.hpp"
#include "rigs/run/fc_setup.hpp"

namespace a3::rigs {
namespace {

TEST(FcSetup, TheDefaultAirframeIsTheFcsDefaultVehicle) {
  const bridge::FcVehicle v = fc_vehicle_from_airframe(dynamics::default_vehicle_params());
  const bridge::FcVehicle d;
  EXPECT_DOUBLE_EQ(v.mass_kg, d.mass_kg);
  EXPECT_DOUBLE_EQ(v.arm_length_m, d.arm_length_m);
  EXPECT_DOUBLE_EQ(v.thrust_coeff_N_per_radps2, d.thrust_coeff_N_per_radps2);
  EXPECT_DOUBLE_EQ(v.torque_coeff_Nm_per_radps2, d.torque_coeff_Nm_per_radps2);
  EXPECT_DOUBLE_EQ(v.max_rotor_speed_radps, d.max_rotor_speed_radps);
  EXPECT_DOUBLE_EQ(v.inertia_zz_kgm2, d.inertia_zz_kgm2);
}

TEST(FcSetup, AnotherAirframeAndPayloadsChangeWhatTheFcIsTold) {
  const dynamics::VehicleParams heavy = dynamics::airframe_by_name_or_path("heavy-lift");
  const bridge::FcVehicle h = fc_vehicle_from_airframe(heavy);
  EXPECT_DOUBLE_EQ(h.mass_kg, heavy.mass_kg);
  EXPECT_NE(h.mass_kg, bridge::FcVehicle{}.mass_kg);
  EXPECT_DOUBLE_EQ(h.thrust_coeff_N_per_radps2, heavy.rotor.thrust_coeff_N_per_radps2);
  dynamics::Payload camera;
  camera.id = "camera";
  camera.mass_kg = 0.35;
  const auto loaded = dynamics::with_payloads(dynamics::default_vehicle_params(), {camera});
  EXPECT_NEAR(fc_vehicle_from_airframe(loaded).mass_kg, 1.5 + 0.35, 1e-12);
  EXPECT_GT(fc_vehicle_from_airframe(loaded).inertia_xx_kgm2, bridge::FcVehicle{}.inertia_xx_kgm2);
}

TEST(FcSetup, GeofenceFromAnInitialState) {
  InitialState state;
  state.alt_bounds = AltitudeBounds{10.0, 120.0};
  state.geofence = {{0, 0}, {200, 0}, {200, 150}, {0, 150}};
  const bridge::Geofence f = geofence_from(state);
  EXPECT_TRUE(f.has_polygon());
  EXPECT_TRUE(f.contains_xy({100, 75}));
  EXPECT_FALSE(f.contains_xy({-1, 75}));
  EXPECT_NEAR(f.distance_to_edge_m({100, 10}), 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(f.min_altitude_m(), 10.0);
  EXPECT_DOUBLE_EQ(f.max_altitude_m(), 120.0);
  // policy.alt_bounds narrows the envelope.
  state.policy_alt_bounds = AltitudeBounds{20.0, 200.0};
  EXPECT_DOUBLE_EQ(geofence_from(state).min_altitude_m(), 20.0);
  EXPECT_DOUBLE_EQ(geofence_from(state).max_altitude_m(), 120.0);
  // No airspace: unbounded.
  const InitialState no_airspace;
  const bridge::Geofence none = geofence_from(no_airspace);
  EXPECT_FALSE(none.has_polygon());
  EXPECT_TRUE(none.altitude_ok(5000.0));
}

TEST(FcSetup, HomePoints) {
  const bridge::Geodetic g = parse_home("47.5,8.25,400");
  EXPECT_DOUBLE_EQ(g.latitude_deg, 47.5);
  EXPECT_DOUBLE_EQ(g.longitude_deg, 8.25);
  EXPECT_DOUBLE_EQ(g.height_m, 400.0);
  EXPECT_DOUBLE_EQ(parse_home(" -33.9, 151.2, 5 ").longitude_deg, 151.2);
  EXPECT_THROW(parse_home("47.5,8.25"), std::invalid_argument);
  EXPECT_THROW(parse_home("47.5;8.25;400"), std::invalid_argument);
  EXPECT_THROW(parse_home("95,8,0"), std::invalid_argument);
  EXPECT_THROW(parse_home("47,8,400,1"), std::invalid_argument);
  EXPECT_THROW(parse_home("nan,8,400"), std::invalid_argument);
}

}  // namespace
}  // namespace a3::rigs
