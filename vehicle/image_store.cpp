// Images on board.
#include "vehicle/image_store.hpp"

#include <cstdio>

namespace a3::vehicle {

const ImageRecord& ImageStore::add(const std::string& sensor, int64_t size_bytes, const Eigen::Vector3d& p_W_m,
                                   double yaw_deg, int64_t utime_us, bool downlinked) {
  char id[32];
  std::snprintf(id, sizeof id, "img-%04zu", records_.size() + 1);
  records_.push_back(ImageRecord{id, sensor, size_bytes, p_W_m, yaw_deg, utime_us, downlinked});
  return records_.back();
}

ImageRecord* ImageStore::find(const std::string& id) {
  for (auto& r : records_) {
    if (r.id == id) return &r;
  }
  return nullptr;
}

}  // namespace a3::vehicle
