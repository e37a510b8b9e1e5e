// Reading JSON input files and fields with errors that say what and where
// ("vehicle.json: /rotor/k_f: expected a number, got string").
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace a3::common {

// Error in an input file; what() names the file, the JSON path and the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses a JSON file (max_bytes guards against huge inputs). Throws InputError.
nlohmann::json load_json_file(const std::filesystem::path& path,
                              std::uintmax_t max_bytes = 64u << 20);

// Field access with context: `where` is e.g. "vehicle.json: /rotor".
double require_number(const nlohmann::json& object, const std::string& key,
                      const std::string& where);
double number_or(const nlohmann::json& object, const std::string& key, double fallback,
                 const std::string& where);
std::string require_string(const nlohmann::json& object, const std::string& key,
                           const std::string& where);
const nlohmann::json& require_object(const nlohmann::json& object, const std::string& key,
                                     const std::string& where);
const nlohmann::json& require_array(const nlohmann::json& object, const std::string& key,
                                    const std::string& where);

}  // namespace a3::common
