// Checks of configuration numbers, one wording for all: "NAME must be a finite number > 0, got V"
// (std::invalid_argument), NAME being where the number came from (e.g. "airframe.mass_kg").
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>

namespace a3::common {

inline void require_positive(double value, const std::string& name) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw std::invalid_argument(name + " must be a finite number > 0, got " + std::to_string(value));
  }
}

inline void require_non_negative(double value, const std::string& name) {
  if (!std::isfinite(value) || value < 0.0) {
    throw std::invalid_argument(name + " must be a finite number >= 0, got " + std::to_string(value));
  }
}

}  // namespace a3::common
