// Violation formatting.
#include "eval/violation.hpp"

namespace a3::eval {

std::string to_string(const Violation& v) {
  return (v.json_path.empty() ? std::string("(root)") : v.json_path) + ": " + v.rule + ": " +
         v.message;
}

}  // namespace a3::eval
