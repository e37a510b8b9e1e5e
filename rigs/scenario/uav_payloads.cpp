// uav.payloads → the dynamics' physical payloads and the sensor suite's declared ones.
#include "rigs/scenario/uav_payloads.hpp"

#include "common/json_file.hpp"

namespace a3::rigs {
namespace {

using common::InputError;

double non_negative_or_zero(const nlohmann::json& item, const char* key, const std::string& where) {
  const double x = common::number_or(item, key, 0.0, where);
  if (x < 0.0) throw InputError(where + "/" + key + ": must be >= 0, got " + std::to_string(x));
  return x;
}

std::string string_or_empty(const nlohmann::json& item, const char* key, const std::string& where) {
  return item.contains(key) ? common::require_string(item, key, where) : std::string();
}

}  // namespace

UavPayloads parse_uav_payloads(const nlohmann::json& payloads, const std::string& json_path) {
  UavPayloads out;
  if (payloads.is_null()) return out;
  if (!payloads.is_array()) throw InputError(json_path + ": payloads must be an array");
  for (std::size_t i = 0; i < payloads.size(); ++i) {
    const std::string w = json_path + "/" + std::to_string(i);
    const auto& item = payloads[i];
    if (!item.is_object()) throw InputError(w + ": a payload must be an object");
    vehicle::DeclaredPayload d;
    d.id = item.contains("id") ? common::require_string(item, "id", w) : "payload" + std::to_string(i);
    d.type = string_or_empty(item, "type", w);
    d.category = string_or_empty(item, "category", w);
    dynamics::Payload p;
    p.id = d.id;
    p.mass_kg = non_negative_or_zero(item, "mass_kg", w);
    p.drag_cdA_m2 = non_negative_or_zero(item, "drag_cdA", w);
    p.power_W = non_negative_or_zero(item, "power_W", w);
    d.power_W = p.power_W;
    out.physical.push_back(std::move(p));
    out.declared.push_back(std::move(d));
  }
  return out;
}

}  // namespace a3::rigs
