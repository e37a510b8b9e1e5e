// The built-in tool catalog (agent/tool_catalog.json), compiled in.
#pragma once

#include <string_view>

namespace a3::agent {

std::string_view tool_catalog_json();

}  // namespace a3::agent
