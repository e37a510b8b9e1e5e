// Plane geometry (common/polygon) and the airspace built on it: no-fly-zone containment,
// clearance and crossing for cylinders and polygons with floors and ceilings, the geofence,
// and traffic plans' positions and velocities between and beyond their points.
#include <gtest/gtest.h>

#include "agent/airspace.hpp"
#include "common/polygon.hpp"

namespace a3::agent {
namespace {

using common::Polygon2d;
using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

const Polygon2d kSquare = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
// An L shape: the square minus its upper-right quarter (concave at (5, 5)).
const Polygon2d kL = {{0, 0}, {10, 0}, {10, 5}, {5, 5}, {5, 10}, {0, 10}};

TEST(Polygon, ContainmentInEitherOrientationAndConcave) {
  EXPECT_TRUE(common::polygon_contains(kSquare, V2(5, 5)));
  EXPECT_FALSE(common::polygon_contains(kSquare, V2(15, 5)));
  Polygon2d reversed(kSquare.rbegin(), kSquare.rend());
  EXPECT_TRUE(common::polygon_contains(reversed, V2(1, 9)));
  EXPECT_TRUE(common::polygon_contains(kL, V2(2, 8)));
  EXPECT_FALSE(common::polygon_contains(kL, V2(8, 8))) << "the missing quarter";
  EXPECT_FALSE(common::polygon_contains({{0, 0}, {1, 1}}, V2(0.5, 0.5))) << "fewer than 3 vertices";
}

TEST(Polygon, DistancesToEdgesAndSegments) {
  EXPECT_DOUBLE_EQ(common::polygon_edge_distance(kSquare, V2(5, 3)), 3.0);
  EXPECT_DOUBLE_EQ(common::polygon_edge_distance(kSquare, V2(13, 14)), 5.0) << "to the corner";
  EXPECT_DOUBLE_EQ(common::polygon_edge_distance(kL, V2(7, 7)), 2.0) << "outside, to the inner corner edges";
  V2 nearest;
  EXPECT_DOUBLE_EQ(common::segment_distance(V2(5, 5), V2(0, 0), V2(10, 0), &nearest), 5.0);
  EXPECT_EQ(nearest, V2(5, 0));
  EXPECT_DOUBLE_EQ(common::segment_distance(V2(-3, 4), V2(0, 0), V2(10, 0)), 5.0);
  EXPECT_DOUBLE_EQ(common::segment_distance(V2(3, 4), V2(0, 0), V2(0, 0)), 5.0) << "a point segment";
}

TEST(Polygon, SegmentCrossings) {
  EXPECT_TRUE(common::segments_intersect(V2(0, 0), V2(10, 10), V2(0, 10), V2(10, 0)));
  EXPECT_FALSE(common::segments_intersect(V2(0, 0), V2(4, 4), V2(0, 10), V2(10, 0)));
  EXPECT_TRUE(common::segments_intersect(V2(0, 0), V2(5, 5), V2(5, 5), V2(9, 0))) << "touching counts";
  EXPECT_FALSE(common::segments_intersect(V2(0, 0), V2(1, 0), V2(2, 0), V2(3, 0))) << "collinear apart";
  EXPECT_TRUE(common::segment_enters_polygon(kSquare, V2(-5, 5), V2(15, 5)));
  EXPECT_TRUE(common::segment_enters_polygon(kSquare, V2(5, 5), V2(50, 50))) << "an end inside";
  EXPECT_FALSE(common::segment_enters_polygon(kSquare, V2(-5, -1), V2(15, -1)));
  EXPECT_FALSE(common::segment_enters_polygon(kL, V2(7, 11), V2(11, 7))) << "across the missing quarter";
  EXPECT_TRUE(common::segment_enters_circle(V2(0, 0), 3.0, V2(-5, 2.9), V2(5, 2.9)));
  EXPECT_FALSE(common::segment_enters_circle(V2(0, 0), 3.0, V2(-5, 3.1), V2(5, 3.1)));
}

NoFlyZone cylinder() {
  NoFlyZone z;
  z.id = "c";
  z.centre = V2(100, 100);
  z.radius_m = 20.0;
  z.floor_m = 10.0;
  z.ceiling_m = 60.0;
  return z;
}

NoFlyZone square_zone() {
  NoFlyZone z;
  z.id = "p";
  z.polygon = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  z.ceiling_m = 50.0;
  return z;
}

TEST(NoFlyZone, ContainmentHonoursFloorAndCeiling) {
  const NoFlyZone c = cylinder();
  EXPECT_TRUE(c.contains(V3(110, 100, 30)));
  EXPECT_FALSE(c.contains(V3(110, 100, 5))) << "below the floor";
  EXPECT_FALSE(c.contains(V3(110, 100, 61))) << "above the ceiling";
  EXPECT_FALSE(c.contains(V3(121, 100, 30)));
  EXPECT_DOUBLE_EQ(c.clearance_m(V2(130, 100)), 10.0);
  EXPECT_DOUBLE_EQ(c.clearance_m(V2(105, 100)), -15.0);
  const NoFlyZone p = square_zone();
  EXPECT_TRUE(p.contains(V3(5, 5, 0)));
  EXPECT_DOUBLE_EQ(p.clearance_m(V2(5, 2)), -2.0);
  EXPECT_DOUBLE_EQ(p.clearance_m(V2(13, 5)), 3.0);
}

TEST(NoFlyZone, CrossingsWithMarginAndAltitude) {
  const NoFlyZone c = cylinder();
  EXPECT_TRUE(c.crossed_by(V3(50, 100, 30), V3(150, 100, 30)));
  EXPECT_FALSE(c.crossed_by(V3(50, 125, 30), V3(150, 125, 30)));
  EXPECT_TRUE(c.crossed_by(V3(50, 125, 30), V3(150, 125, 30), 6.0)) << "within the margin";
  EXPECT_FALSE(c.crossed_by(V3(50, 100, 70), V3(150, 100, 80))) << "over the ceiling";
  EXPECT_TRUE(c.crossed_by(V3(50, 100, 5), V3(150, 100, 70))) << "climbing through its extent";
  const NoFlyZone p = square_zone();
  EXPECT_TRUE(p.crossed_by(V3(-5, 5, 20), V3(15, 5, 20)));
  EXPECT_FALSE(p.crossed_by(V3(-5, 12, 20), V3(15, 12, 20)));
  EXPECT_TRUE(p.crossed_by(V3(-5, 12, 20), V3(15, 12, 20), 2.5)) << "2 m from its edge, 2.5 m margin";
  EXPECT_TRUE(p.crossed_by(V3(12, 12, 20), V3(12, 30, 20), 3.0)) << "the corner within the margin";
  EXPECT_FALSE(p.crossed_by(V3(13.5, 12, 20), V3(13.5, 30, 20), 3.0));
}

TEST(Airspace, GeofenceEnvelopeAndZoneLookup) {
  Airspace a;
  EXPECT_TRUE(a.inside_geofence(V2(1e6, -1e6))) << "no geofence: unbounded";
  EXPECT_TRUE(std::isinf(a.geofence_clearance_m(V2(0, 0))));
  a.geofence = kSquare;
  a.min_altitude_m = 10;
  a.max_altitude_m = 100;
  a.no_fly_zones = {square_zone()};
  EXPECT_DOUBLE_EQ(a.geofence_clearance_m(V2(2, 5)), 2.0);
  EXPECT_DOUBLE_EQ(a.geofence_clearance_m(V2(-3, 5)), -3.0);
  EXPECT_TRUE(a.altitude_ok(10.0));
  EXPECT_TRUE(a.altitude_ok(100.0)) << "bounds are inside";
  EXPECT_FALSE(a.altitude_ok(100.01));
  ASSERT_NE(a.zone_containing(V3(5, 5, 20)), nullptr);
  EXPECT_EQ(a.zone_containing(V3(5, 5, 20))->id, "p");
  EXPECT_EQ(a.zone_containing(V3(5, 5, 55)), nullptr);
}

TEST(TrafficPlan, InterpolatesAndHoldsAtTheEnds) {
  TrafficPlan plan;
  plan.path = {{10.0, V3(0, 0, 40)}, {20.0, V3(100, 0, 40)}, {30.0, V3(100, 50, 60)}};
  EXPECT_EQ(plan.position_at(0.0), V3(0, 0, 40)) << "before the first point: there";
  EXPECT_EQ(plan.position_at(15.0), V3(50, 0, 40));
  EXPECT_EQ(plan.position_at(25.0), V3(100, 25, 50));
  EXPECT_EQ(plan.position_at(99.0), V3(100, 50, 60)) << "after the last: holds";
  EXPECT_EQ(plan.velocity_at(15.0), V3(10, 0, 0));
  EXPECT_EQ(plan.velocity_at(25.0), V3(0, 5, 2));
  EXPECT_EQ(plan.velocity_at(5.0), V3::Zero());
  EXPECT_EQ(plan.velocity_at(35.0), V3::Zero());
  EXPECT_EQ(TrafficPlan{}.position_at(3.0), V3::Zero());
}

}  // namespace
}  // namespace a3::agent
