// One reference token of a JSON Pointer (RFC 6901): "~" written "~0", "/" written "~1".
#pragma once

#include <string>
#include <string_view>

namespace a3::common {

std::string json_pointer_token(std::string_view key);

}  // namespace a3::common
