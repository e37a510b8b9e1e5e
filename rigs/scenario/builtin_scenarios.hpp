// The built-in scenarios (rigs/scenarios/*.json), compiled in: name → JSON text.
#pragma once

#include <string_view>
#include <utility>
#include <vector>

namespace a3::rigs {

const std::vector<std::pair<std::string_view, std::string_view>>& builtin_scenarios();

}  // namespace a3::rigs
