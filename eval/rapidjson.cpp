// The RapidJSON assertion handler.
#include "eval/rapidjson.hpp"

#include <string>

namespace a3::eval {

void rapidjson_assertion_failed(const char* condition, const char* file, int line) {
  throw std::logic_error(std::string("RapidJSON assertion failed: ") + condition + " (" + file +
                         ":" + std::to_string(line) + ")");
}

}  // namespace a3::eval
