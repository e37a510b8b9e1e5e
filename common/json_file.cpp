// JSON input helpers.
#include "common/json_file.hpp"

#include "common/json_text.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace a3::common {
namespace {

const nlohmann::json& require_field(const nlohmann::json& object, const std::string& key,
                                    const std::string& where) {
  if (!object.is_object()) {
    throw InputError(where + ": expected an object, got " + std::string(object.type_name()));
  }
  auto it = object.find(key);
  if (it == object.end()) throw InputError(where + "/" + key + ": missing");
  return *it;
}

}  // namespace

nlohmann::json load_json_file(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string() + ": cannot read: " + ec.message());
  if (size > max_bytes) {
    throw InputError(path.string() + ": file is " + std::to_string(size) +
                     " bytes, more than the limit of " + std::to_string(max_bytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open");
  std::stringstream buffer;
  buffer << in.rdbuf();
  JsonLimits limits;
  limits.max_bytes = static_cast<std::size_t>(max_bytes);
  return parse_json_text(buffer.str(), path.string(), limits);
}

double require_number(const nlohmann::json& object, const std::string& key,
                      const std::string& where) {
  const auto& value = require_field(object, key, where);
  if (!value.is_number()) {
    throw InputError(where + "/" + key + ": expected a number, got " +
                     std::string(value.type_name()));
  }
  const double x = value.get<double>();
  if (!std::isfinite(x)) throw InputError(where + "/" + key + ": not a finite number");
  return x;
}

double number_or(const nlohmann::json& object, const std::string& key, double fallback,
                 const std::string& where) {
  if (!object.is_object()) {
    throw InputError(where + ": expected an object, got " + std::string(object.type_name()));
  }
  if (!object.contains(key)) return fallback;
  return require_number(object, key, where);
}

std::string require_string(const nlohmann::json& object, const std::string& key,
                           const std::string& where) {
  const auto& value = require_field(object, key, where);
  if (!value.is_string()) {
    throw InputError(where + "/" + key + ": expected a string, got " +
                     std::string(value.type_name()));
  }
  return value.get<std::string>();
}

const nlohmann::json& require_object(const nlohmann::json& object, const std::string& key,
                                     const std::string& where) {
  const auto& value = require_field(object, key, where);
  if (!value.is_object()) {
    throw InputError(where + "/" + key + ": expected an object, got " +
                     std::string(value.type_name()));
  }
  return value;
}

const nlohmann::json& require_array(const nlohmann::json& object, const std::string& key,
                                    const std::string& where) {
  const auto& value = require_field(object, key, where);
  if (!value.is_array()) {
    throw InputError(where + "/" + key + ": expected an array, got " +
                     std::string(value.type_name()));
  }
  return value;
}

}  // namespace a3::common
