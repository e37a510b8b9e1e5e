// Processor-sharing edge delay.
#include "linkemu/edge_compute.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace a3::linkemu {

double EdgeComputeModel::delay_ms(double work_ms, double edge_load) const {
  if (!std::isfinite(work_ms) || work_ms < 0.0) {
    std::ostringstream message;
    message << "work_ms must be a finite number >= 0, got " << work_ms;
    throw std::invalid_argument(message.str());
  }
  const double load = std::clamp(edge_load, 0.0, max_load);
  return work_ms / (1.0 - load);
}

}  // namespace a3::linkemu
