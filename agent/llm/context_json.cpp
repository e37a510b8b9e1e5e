// AgentContext ⇄ JSON.
#include "agent/llm/context_json.hpp"

#include "agent/mission/mission.hpp"

#include <stdexcept>

#include "agent/llm/json_extract.hpp"
#include "common/json_text.hpp"

namespace a3::agent::llm {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument(where + ": " + what);
}

const nlohmann::json& field(const nlohmann::json& o, const char* key, const std::string& where) {
  if (!o.is_object()) fail(where, "expected an object");
  if (!o.contains(key)) fail(where + "/" + key, "missing");
  return o[key];
}

double number_field(const nlohmann::json& o, const char* key, const std::string& where) {
  const auto& v = field(o, key, where);
  if (!v.is_number()) fail(where + "/" + key, std::string("expected a number, got ") + v.type_name());
  return v.get<double>();
}

double number_or(const nlohmann::json& o, const char* key, double fallback, const std::string& where) {
  return o.contains(key) ? number_field(o, key, where) : fallback;
}

int int_field(const nlohmann::json& o, const char* key, const std::string& where) {
  const auto& v = field(o, key, where);
  if (!v.is_number_integer()) fail(where + "/" + key, std::string("expected an integer, got ") + v.type_name());
  return v.get<int>();
}

std::string string_field(const nlohmann::json& o, const char* key, const std::string& where) {
  const auto& v = field(o, key, where);
  if (!v.is_string()) fail(where + "/" + key, std::string("expected a string, got ") + v.type_name());
  return v.get<std::string>();
}

std::string string_or(const nlohmann::json& o, const char* key, const std::string& fallback, const std::string& where) {
  return o.contains(key) ? string_field(o, key, where) : fallback;
}

const nlohmann::json& array_field(const nlohmann::json& o, const char* key, const std::string& where) {
  const auto& v = field(o, key, where);
  if (!v.is_array()) fail(where + "/" + key, std::string("expected an array, got ") + v.type_name());
  return v;
}

Eigen::Vector2d point2(const nlohmann::json& v, const std::string& where) {
  if (!v.is_array() || v.size() < 2 || !v[0].is_number() || !v[1].is_number()) fail(where, "expected [x, y]");
  return {v[0].get<double>(), v[1].get<double>()};
}

ObjectiveType objective_type(const std::string& name, const std::string& where) {
  for (const auto t : {ObjectiveType::kSurvey, ObjectiveType::kImagePoint, ObjectiveType::kDelivery,
                       ObjectiveType::kThermalSearch, ObjectiveType::kReturnAndLand}) {
    if (name == to_string(t)) return t;
  }
  fail(where, "unknown objective type '" + name +
                  "' (survey, image_point, delivery, thermal_search, return_and_land)");
}

// An observation cut to its status when the dialogue is too long for the prompt.
nlohmann::json shortened_observation(const nlohmann::json& o) {
  if (!o.is_object()) return o;
  if (o.contains("task")) {
    return {{"task", o.value("task", "")}, {"from", o.value("from", "")}, {"status", o.value("status", "")},
            {"payload", {{"shortened", true}}}};
  }
  std::string status = "ok";
  if (o.contains("result") && o["result"].is_object()) status = o["result"].value("status", "ok");
  return {{"tool", o.value("tool", "")}, {"result", {{"status", status}, {"shortened", true}}}};
}

}  // namespace

nlohmann::json mission_to_json(const Mission& m) { return mission_brief_json(m); }

Mission mission_from_json(const nlohmann::json& j, const std::string& where) {
  Mission m;
  if (!j.is_object()) fail(where, "expected an object");
  m.name = string_or(j, "name", "", where);
  m.description = string_or(j, "description", "", where);
  const auto& home = array_field(j, "home", where);
  if (home.size() != 3 || !home[0].is_number() || !home[1].is_number() || !home[2].is_number()) {
    fail(where + "/home", "expected [x, y, z]");
  }
  m.home_W_m = {home[0].get<double>(), home[1].get<double>(), home[2].get<double>()};
  m.cruise_altitude_m = number_field(j, "cruise_altitude_m", where);
  m.cruise_speed_mps = number_or(j, "cruise_speed_mps", m.cruise_speed_mps, where);
  m.time_limit_s = number_or(j, "time_limit_s", m.time_limit_s, where);
  const auto& objectives = array_field(j, "objectives", where);
  for (std::size_t i = 0; i < objectives.size(); ++i) {
    const std::string w = where + "/objectives/" + std::to_string(i);
    const auto& oj = objectives[i];
    Objective o;
    o.id = string_field(oj, "id", w);
    o.type = objective_type(string_field(oj, "type", w), w + "/type");
    o.description = string_or(oj, "description", "", w);
    o.radius_m = number_or(oj, "radius_m", o.radius_m, w);
    o.altitude_m = number_or(oj, "altitude_m", o.altitude_m, w);
    o.sensor = string_or(oj, "sensor", o.sensor, w);
    o.drop_altitude_m = number_or(oj, "drop_altitude_m", o.drop_altitude_m, w);
    if (oj.contains("images_required")) o.images_required = int_field(oj, "images_required", w);
    if (o.type == ObjectiveType::kSurvey || o.type == ObjectiveType::kThermalSearch) {
      const auto& area = array_field(oj, "area", w);
      for (std::size_t k = 0; k < area.size(); ++k) o.area.push_back(point2(area[k], w + "/area/" + std::to_string(k)));
      if (o.area.size() < 3) fail(w + "/area", "needs at least 3 points");
    }
    if (o.type == ObjectiveType::kImagePoint || o.type == ObjectiveType::kDelivery) {
      o.point = point2(field(oj, "point", w), w + "/point");
    }
    m.objectives.push_back(std::move(o));
  }
  return m;
}

nlohmann::json turn_to_json(const Turn& t) {
  return {{"turn", t.number}, {"speaker", t.speaker}, {"intent", t.intent}, {"text", t.text},
          {"actions", t.actions}, {"obs", t.obs},       {"net", t.net},       {"t_s", t.started_s}};
}

nlohmann::json context_to_json(const AgentContext& c, const DialogueLimits& limits) {
  nlohmann::json dialogue = nlohmann::json::array();
  if (c.dialogue != nullptr) {
    for (const Turn& t : *c.dialogue) dialogue.push_back(turn_to_json(t));
  }
  // Too long for the prompt: the oldest turns keep what was said and done, and only the status
  // of what came back, until the dialogue fits (the newest turns are always kept whole).
  std::size_t shortened = 0;
  std::size_t length = dialogue.dump().size();
  while (length > limits.max_dialogue_chars && shortened + limits.keep_full_turns < dialogue.size()) {
    auto& obs = dialogue[shortened]["obs"];
    if (obs.is_array()) {
      for (auto& o : obs) o = shortened_observation(o);
    }
    ++shortened;
    length = dialogue.dump().size();
  }
  nlohmann::json out = {{kContextMarker, kContextVersion},
                        {"turn", c.turn_number},
                        {"max_turns", c.max_turns},
                        {"mission_time_s", c.mission_time_s},
                        {"mission", c.mission != nullptr ? mission_to_json(*c.mission) : nlohmann::json(nullptr)},
                        {"initial_state", c.initial_state},
                        {"airspace", c.airspace},
                        {"net", c.net},
                        {"telemetry", c.last_telemetry},
                        {"dialogue", dialogue}};
  if (shortened > 0) out["dialogue_shortened"] = shortened;
  return out;
}

AgentContext RebuiltContext::view(const ToolCatalog& tools) const {
  AgentContext c;
  c.mission = &mission;
  c.initial_state = initial_state;
  c.airspace = airspace;
  c.dialogue = &dialogue;
  c.tools = &tools;
  c.net = net;
  c.last_telemetry = telemetry;
  c.turn_number = turn_number;
  c.max_turns = max_turns;
  c.mission_time_s = mission_time_s;
  return c;
}

RebuiltContext context_from_json(const nlohmann::json& j) {
  const std::string where = "context";
  if (!j.is_object()) fail(where, "expected an object");
  if (!j.contains(kContextMarker) || !j[kContextMarker].is_number_integer() ||
      j[kContextMarker].get<int>() != kContextVersion) {
    fail(where + "/" + kContextMarker, "expected " + std::to_string(kContextVersion));
  }
  RebuiltContext r;
  r.turn_number = int_field(j, "turn", where);
  r.max_turns = int_field(j, "max_turns", where);
  r.mission_time_s = number_or(j, "mission_time_s", 0.0, where);
  r.mission = mission_from_json(field(j, "mission", where), where + "/mission");
  r.initial_state = j.value("initial_state", nlohmann::json::object());
  r.airspace = j.value("airspace", nlohmann::json::object());
  r.net = j.value("net", nlohmann::json::object());
  r.telemetry = j.contains("telemetry") ? j["telemetry"] : nlohmann::json(nullptr);
  if (!r.airspace.is_object()) fail(where + "/airspace", "expected an object");
  if (!r.net.is_object()) fail(where + "/net", "expected an object");
  const auto& dialogue = array_field(j, "dialogue", where);
  for (std::size_t i = 0; i < dialogue.size(); ++i) {
    const std::string w = where + "/dialogue/" + std::to_string(i);
    const auto& tj = dialogue[i];
    Turn t;
    t.number = int_field(tj, "turn", w);
    t.speaker = string_field(tj, "speaker", w);
    if (t.speaker != "agent" && t.speaker != "user") fail(w + "/speaker", "expected \"agent\" or \"user\", got \"" + t.speaker + "\"");
    t.intent = string_or(tj, "intent", "", w);
    t.text = string_or(tj, "text", "", w);
    t.actions = array_field(tj, "actions", w);
    t.obs = array_field(tj, "obs", w);
    t.net = tj.value("net", nlohmann::json::object());
    t.started_s = number_or(tj, "t_s", 0.0, w);
    r.dialogue.push_back(std::move(t));
  }
  return r;
}

std::optional<nlohmann::json> find_context_block(const std::string& text) {
  for (const auto& span : top_level_object_spans(text)) {
    if (!span.closed) continue;
    auto j = common::try_parse_json_text(std::string_view(text).substr(span.begin, span.end - span.begin));
    if (j && j->is_object() && j->contains(kContextMarker)) return j;
  }
  return std::nullopt;
}

}  // namespace a3::agent::llm
