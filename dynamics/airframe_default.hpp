// The built-in airframes (dynamics/airframes/*.json), compiled in: "iris" (the default) and
// "heavy-lift".
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace a3::dynamics {

std::string_view default_airframe_json();
// The JSON text of a built-in airframe; throws std::invalid_argument naming the known ones.
std::string_view builtin_airframe_json(std::string_view name);
std::vector<std::string> builtin_airframe_names();

}  // namespace a3::dynamics
