// Link message envelopes.
#include "agent/link_protocol.hpp"

#include <algorithm>
#include <limits>
#include <string_view>

#include "common/json_text.hpp"

namespace a3::agent {
namespace {

a3lcm::link_message_t make(const nlohmann::json& body, const std::string& kind, int64_t id, int64_t utime_us,
                           const std::string& sender, int64_t extra_bytes) {
  a3lcm::link_message_t m;
  const std::string text = common::dump_json_text(body);
  m.utime_us = utime_us;
  m.sent_utime_us = utime_us;
  m.message_id = id;
  m.sender = sender;
  m.kind = kind;
  m.payload.assign(text.begin(), text.end());
  m.payload_length = static_cast<int32_t>(m.payload.size());
  const int64_t size = static_cast<int64_t>(text.size()) + std::max<int64_t>(extra_bytes, 0);
  m.payload_size_bytes = static_cast<int32_t>(std::min<int64_t>(size, std::numeric_limits<int32_t>::max()));
  return m;
}

std::optional<nlohmann::json> parse(const a3lcm::link_message_t& m, std::string* error) {
  if (m.payload.size() > kMaxLinkJsonBytes) {
    *error = "link message of " + std::to_string(m.payload.size()) + " bytes is over the limit";
    return std::nullopt;
  }
  // An action whose args nest as deep as a reply may (common/json_text's default), a few levels down.
  common::JsonLimits limits;
  limits.max_depth += 8;
  std::string problem;
  auto parsed = common::try_parse_json_text(std::string_view(reinterpret_cast<const char*>(m.payload.data()), m.payload.size()), &problem, limits);
  if (!parsed || !parsed->is_object()) {
    *error = "link message " + std::to_string(m.message_id) + " is not a JSON object" +
             (parsed ? std::string() : " (" + problem + ")");
    return std::nullopt;
  }
  nlohmann::json& j = *parsed;
  if (!j.contains("turn") || !j["turn"].is_number_integer() || !j.contains("action_index") ||
      !j["action_index"].is_number_integer()) {
    *error = "link message " + std::to_string(m.message_id) + " lacks integer turn/action_index";
    return std::nullopt;
  }
  return j;
}

}  // namespace

a3lcm::link_message_t encode_action(const ActionEnvelope& a, int64_t id, int64_t utime_us, const std::string& sender) {
  const std::string kind = a.action.value("type", "") == "a2a" ? "a2a_message" : "mcp_call";
  return make({{"turn", a.turn}, {"action_index", a.action_index}, {"action", a.action}}, kind, id, utime_us, sender, 0);
}

a3lcm::link_message_t encode_observation(const ObservationEnvelope& o, int64_t id, int64_t utime_us,
                                         const std::string& sender, int64_t extra_bytes) {
  return make({{"turn", o.turn}, {"action_index", o.action_index}, {"obs", o.obs}},
              extra_bytes > 0 ? "image" : "observation", id, utime_us, sender, extra_bytes);
}

std::optional<ActionEnvelope> decode_action(const a3lcm::link_message_t& m, std::string* error) {
  auto j = parse(m, error);
  if (!j) return std::nullopt;
  if (!j->contains("action") || !(*j)["action"].is_object()) {
    *error = "link message " + std::to_string(m.message_id) + " has no action object";
    return std::nullopt;
  }
  return ActionEnvelope{(*j)["turn"].get<int>(), (*j)["action_index"].get<int>(), (*j)["action"]};
}

std::optional<ObservationEnvelope> decode_observation(const a3lcm::link_message_t& m, std::string* error) {
  auto j = parse(m, error);
  if (!j) return std::nullopt;
  if (!j->contains("obs") || !(*j)["obs"].is_object()) {
    *error = "link message " + std::to_string(m.message_id) + " has no obs object";
    return std::nullopt;
  }
  return ObservationEnvelope{(*j)["turn"].get<int>(), (*j)["action_index"].get<int>(), (*j)["obs"]};
}

}  // namespace a3::agent
