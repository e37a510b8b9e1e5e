// Turn → episode JSON, and the status of an observation.
#include "agent/conversation/turn.hpp"

namespace a3::agent {

nlohmann::json Turn::to_json() const {
  return {{"turn", number}, {"speaker", speaker}, {"intent", intent},
          {"actions", actions}, {"obs", obs},   {"net", net}};
}

std::string Turn::answer_status(std::size_t i) const {
  return observation_status(i < obs.size() ? obs[i] : nlohmann::json());
}

std::string observation_status(const nlohmann::json& obs) {
  if (!obs.is_object()) return "timeout";
  const nlohmann::json& answer = obs.contains("result") ? obs["result"] : obs;
  if (!answer.is_object()) return "timeout";
  return answer.contains("status") && answer["status"].is_string() ? answer["status"].get<std::string>() : "";
}

}  // namespace a3::agent
