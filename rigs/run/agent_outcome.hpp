// No silent success: what the recorded turns say about the agent, for the run's status.
// - endpoint_failed: kEndpointFailedTurns (2) agent turns in a row failed at the HTTP/network
//   level (every attempt of the turn gave up; the last one's failure was the endpoint's:
//   attempt_log entry "endpoint_failure": true, as agent::llm::is_endpoint_failure judges it).
//   The run ends at once: an endpoint that failed for good would fail every later turn too.
// - agent_failed: the run is over and no agent turn carried an action (an agent that never
//   produced a valid action; its turns are recorded with their errors).
// Both read only the recorded turns (RecordedEpisode::turns, with their _rig part), as the
// episode writes them.
// - never_flew: the agent acted, but the vehicle never left the ground although the mission
//   has objectives (a replayed episode that never takes off, a take-off lost on the link and
//   never sent again): an episode that flew nothing is not "completed".
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace a3::rigs {

inline constexpr int kEndpointFailedTurns = 2;

// "endpoint_failed: <n> agent turns in a row failed at the endpoint; last: <error>", or "".
std::string endpoint_failure_status(const std::vector<nlohmann::json>& turns);

// "agent_failed: no agent turn had a valid action (<n> agent turns; last error: ...)", or "".
std::string agent_failure_status(const std::vector<nlohmann::json>& turns);

// "never_flew: the vehicle never left the ground (highest <z> m) though the mission has <n>
// objectives", or "" when it flew or the mission needs no flight (no objectives).
std::string never_flew_status(bool has_flown, double max_altitude_m, std::size_t objectives);

}  // namespace a3::rigs
