// The images captured on board: id, sensor, size, where (true position) and whether their
// bytes have gone down the link yet.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace a3::vehicle {

struct ImageRecord {
  std::string id;  // "img-0001", ...
  std::string sensor;
  int64_t size_bytes = 0;
  Eigen::Vector3d p_W_m = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;
  int64_t utime_us = 0;
  bool downlinked = false;
};

class ImageStore {
 public:
  // Adds a record with the next id and returns it.
  const ImageRecord& add(const std::string& sensor, int64_t size_bytes, const Eigen::Vector3d& p_W_m, double yaw_deg,
                         int64_t utime_us, bool downlinked);
  ImageRecord* find(const std::string& id);
  const std::vector<ImageRecord>& records() const { return records_; }
  std::vector<ImageRecord>& records() { return records_; }

 private:
  std::vector<ImageRecord> records_;
};

}  // namespace a3::vehicle
