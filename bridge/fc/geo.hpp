// Local ENU coordinates around a home point and WGS-84 geodetic coordinates, as GNSS receivers
// report them: a flat-earth (local tangent plane) conversion with the ellipsoid's radii of
// curvature at home, accurate to centimetres within 10 km of it.
#pragma once

#include <Eigen/Core>

namespace a3::bridge {

struct Geodetic {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double height_m = 0.0;  // above the ellipsoid
};

// Where ENU (0, 0, 0) is: PX4's default SITL home (Zürich, Irchel park), for lack of a better
// convention; scenarios may set their own.
inline constexpr Geodetic kDefaultHome{47.397742, 8.545594, 488.0};

class LocalFrame {
 public:
  explicit LocalFrame(const Geodetic& home = kDefaultHome);
  Geodetic to_geodetic(const Eigen::Vector3d& p_W_m) const;
  Eigen::Vector3d to_enu(const Geodetic& g) const;
  const Geodetic& home() const { return home_; }

 private:
  Geodetic home_;
  double metres_per_deg_lat_;
  double metres_per_deg_lon_;
};

}  // namespace a3::bridge
