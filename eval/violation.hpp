// One reason an episode file is invalid: where (JSON Pointer into the file), which rule, and
// a message a person can act on.
#pragma once

#include <string>
#include <vector>

namespace a3::eval {

struct Violation {
  std::string json_path;  // RFC 6901 pointer, "" for the whole document
  std::string rule;       // e.g. "json-syntax", "schema", "role", "alternation", "turn-count"
  std::string message;
};

using Violations = std::vector<Violation>;

// "/dialogue/3/speaker: role: speaker 'system' is not agent or user"
std::string to_string(const Violation& v);

}  // namespace a3::eval
