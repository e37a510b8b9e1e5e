// Mission description.
#include "agent/mission/mission.hpp"

#include "agent/mission/objective_rules.hpp"

namespace a3::agent {

const char* to_string(ObjectiveType t) {
  switch (t) {
    case ObjectiveType::kSurvey: return "survey";
    case ObjectiveType::kImagePoint: return "image_point";
    case ObjectiveType::kDelivery: return "delivery";
    case ObjectiveType::kThermalSearch: return "thermal_search";
    case ObjectiveType::kReturnAndLand: return "return_and_land";
  }
  return "unknown";
}

nlohmann::json mission_brief_json(const Mission& m) {
  nlohmann::json objectives = nlohmann::json::array();
  for (const Objective& o : m.objectives) {
    nlohmann::json j = {{"id", o.id}, {"type", to_string(o.type)}, {"description", o.description}, {"radius_m", o.radius_m}};
    switch (o.type) {
      case ObjectiveType::kSurvey:
      case ObjectiveType::kThermalSearch: {
        nlohmann::json area = nlohmann::json::array();
        for (const auto& p : o.area) area.push_back({p.x(), p.y()});
        j["area"] = area;
        j["altitude_m"] = o.altitude_m;
        j["sensor"] = o.sensor;
        if (o.type == ObjectiveType::kSurvey) j["images_required"] = o.images_required;
        break;
      }
      case ObjectiveType::kImagePoint:
        j["point"] = {o.point.x(), o.point.y()};
        j["sensor"] = o.sensor;
        j["altitude_m"] = o.altitude_m;
        break;
      case ObjectiveType::kDelivery:
        j["point"] = {o.point.x(), o.point.y()};
        j["drop_altitude_m"] = o.drop_altitude_m;
        break;
      case ObjectiveType::kReturnAndLand:
        j["home"] = {m.home_W_m.x(), m.home_W_m.y()};
        break;
    }
    j["judged"] = objective_rule_text(o);
    objectives.push_back(j);
  }
  return {{"name", m.name},
          {"description", m.description},
          {"home", {m.home_W_m.x(), m.home_W_m.y(), m.home_W_m.z()}},
          {"cruise_altitude_m", m.cruise_altitude_m},
          {"cruise_speed_mps", m.cruise_speed_mps},
          {"time_limit_s", m.time_limit_s},
          {"objectives", objectives}};
}

}  // namespace a3::agent
