// Local tangent plane ↔ WGS-84.
#include "bridge/fc/geo.hpp"

#include <cmath>

namespace a3::bridge {
namespace {
constexpr double kSemiMajor_m = 6378137.0;
constexpr double kEccentricity2 = 6.69437999014e-3;
constexpr double kDeg = M_PI / 180.0;
}  // namespace

LocalFrame::LocalFrame(const Geodetic& home) : home_(home) {
  const double s = std::sin(home.latitude_deg * kDeg);
  const double w = std::sqrt(1.0 - kEccentricity2 * s * s);
  const double meridian_m = kSemiMajor_m * (1.0 - kEccentricity2) / (w * w * w);
  const double prime_vertical_m = kSemiMajor_m / w;
  metres_per_deg_lat_ = (meridian_m + home.height_m) * kDeg;
  metres_per_deg_lon_ = (prime_vertical_m + home.height_m) * std::cos(home.latitude_deg * kDeg) * kDeg;
}

Geodetic LocalFrame::to_geodetic(const Eigen::Vector3d& p) const {
  return {home_.latitude_deg + p.y() / metres_per_deg_lat_,
          home_.longitude_deg + p.x() / metres_per_deg_lon_, home_.height_m + p.z()};
}

Eigen::Vector3d LocalFrame::to_enu(const Geodetic& g) const {
  return {(g.longitude_deg - home_.longitude_deg) * metres_per_deg_lon_,
          (g.latitude_deg - home_.latitude_deg) * metres_per_deg_lat_, g.height_m - home_.height_m};
}

}  // namespace a3::bridge
