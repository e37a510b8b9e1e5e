// The flight controller keeps out of no-fly zones as it keeps inside the geofence (issue 35):
// a go-to aimed through a zone, with the wind pushing it on, stops at the zone's edge and
// holds there; a go-to whose line grazes a zone slides along it and arrives; the same flights
// without the zones in the fc's parameters enter them (the brake is what keeps them out).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "common/no_fly_zone.hpp"
#include "dynamics/vehicle_params.hpp"
#include "tests/fc/direct_loop.hpp"

namespace a3::bridge {
namespace {

using a3::test::DirectLoop;

constexpr double kAltitude_m = 20.0;
constexpr double kCruise_mps = 8.0;

common::NoFlyZone cylinder(double x, double y, double radius_m) {
  common::NoFlyZone z;
  z.id = "cylinder";
  z.centre = {x, y};
  z.radius_m = radius_m;
  z.floor_m = 0.0;
  z.ceiling_m = 120.0;
  return z;
}

common::NoFlyZone square(double x0, double y0, double side_m) {
  common::NoFlyZone z;
  z.id = "square";
  z.polygon = {{x0, y0}, {x0 + side_m, y0}, {x0 + side_m, y0 + side_m}, {x0, y0 + side_m}};
  z.floor_m = 0.0;
  z.ceiling_m = 120.0;
  return z;
}

struct ZoneFlight {
  double min_clearance_m = 1e9;  // nearest the vehicle came to the zone (negative: inside)
  double final_speed_mps = 0.0;
  bool arrived = false;
};

// Takes off to 20 m at the origin, then flies a go-to to (x, y) for `flight_s` seconds in a
// wind from `wind_from_deg` at `wind_mps` with gusts, the zone known to the fc or not.
ZoneFlight fly(const common::NoFlyZone& zone, bool fc_knows_zone, double x, double y, double wind_mps,
               double wind_from_deg, double flight_s,
               const dynamics::VehicleParams& vehicle = dynamics::default_vehicle_params()) {
  FcParams params = a3::test::fc_params_for(vehicle);
  if (fc_knows_zone) params.no_fly_zones = {zone};
  DirectLoop loop(vehicle, params, dynamics::wind_from_report(wind_mps, wind_from_deg), 3, true);
  loop.run_until(1.0);
  FlightCommand takeoff;
  takeoff.kind = FlightCommandKind::kTakeoff;
  takeoff.target_W_m = {0, 0, kAltitude_m};
  EXPECT_TRUE(loop.command(takeoff).accepted);
  loop.run_until(25.0);
  FlightCommand go;
  go.kind = FlightCommandKind::kGoto;
  go.target_W_m = {x, y, kAltitude_m};
  go.speed_limit_mps = kCruise_mps;
  EXPECT_TRUE(loop.command(go).accepted);
  ZoneFlight f;
  loop.run_until(loop.time_s() + flight_s, [&](double) {
    f.min_clearance_m = std::min(f.min_clearance_m, zone.clearance_m(loop.vehicle().state().p_W_m.head<2>()));
  });
  f.final_speed_mps = loop.vehicle().state().v_W_mps.norm();
  f.arrived = loop.fc().status().mode == FcMode::kHold;
  return f;
}

// Sent through `zone` to (300, y) with a 7 m/s tailwind and gusts: with the brake it stops
// outside the zone and holds there; without, it flies deep into it.
void expect_stops_outside(const common::NoFlyZone& zone, double y, const std::string& what) {
  const ZoneFlight braked = fly(zone, true, 300.0, y, 7.0, 270.0, 90.0);
  const ZoneFlight unbraked = fly(zone, false, 300.0, y, 7.0, 270.0, 90.0);
  std::cout << "go-to through " << what << ", 7 m/s tailwind with gusts: nearest " << braked.min_clearance_m
            << " m outside (without the brake " << unbraked.min_clearance_m << " m)\n";
  EXPECT_LT(unbraked.min_clearance_m, -30.0);
  EXPECT_GE(braked.min_clearance_m, 0.0);
  EXPECT_FALSE(braked.arrived);
  EXPECT_LT(braked.final_speed_mps, 1.5);  // holding at the edge, not creeping in
}

TEST(NoFlyZoneBrake, StopsAtTheEdgeOfACylinderItIsSentThroughWithTheWindBehind) {
  expect_stops_outside(cylinder(150.0, 0.0, 40.0), 0.0, "a 40 m cylinder");
}

TEST(NoFlyZoneBrake, StopsAtTheEdgeOfAPolygonZone) {
  expect_stops_outside(square(120.0, -60.0, 120.0), 10.0, "a 120 m square");
}

TEST(NoFlyZoneBrake, AHeavyLiftVehicleStopsAtTheEdgeToo) {
  const common::NoFlyZone zone = cylinder(150.0, 0.0, 40.0);
  const dynamics::VehicleParams heavy = dynamics::airframe_by_name_or_path("heavy-lift");
  const ZoneFlight braked = fly(zone, true, 300.0, 0.0, 7.0, 270.0, 90.0, heavy);
  std::cout << "heavy-lift go-to through a 40 m cylinder, 7 m/s tailwind with gusts: nearest "
            << braked.min_clearance_m << " m outside\n";
  EXPECT_GE(braked.min_clearance_m, 0.0);
  EXPECT_FALSE(braked.arrived);
}

// The line passes 1 m outside the cylinder, inside the brake's 2 m: the vehicle is slid
// around the zone's edge (the crosswind from the north pushes it toward the zone) and arrives.
TEST(NoFlyZoneBrake, SlidesAlongAZoneItsLineGrazesAndArrives) {
  const common::NoFlyZone zone = cylinder(150.0, 41.0, 40.0);
  const ZoneFlight braked = fly(zone, true, 300.0, 0.0, 6.0, 0.0, 90.0);
  std::cout << "go-to grazing a 40 m cylinder, 6 m/s crosswind toward it with gusts: nearest "
            << braked.min_clearance_m << " m outside, arrived " << braked.arrived << "\n";
  EXPECT_GE(braked.min_clearance_m, 0.0);
  EXPECT_TRUE(braked.arrived);
}

}  // namespace
}  // namespace a3::bridge
