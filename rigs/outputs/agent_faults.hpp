// Faults inside the agent, read from its own dialogue (issue 35): what a competent operator would
// not have done whatever the link did. Two kinds, each recorded with the agent turn it shows in:
//   refused_repeated     a command the safety gate refused ("refused") sent again with the same
//                        arguments and refused again: the agent did not re-plan;
//   timeout_not_retried  a command that changes the vehicle (an MCP tool whose catalogue kind is
//                        not "query") answered timeout (lost, or unanswered) and never sent again
//                        although the agent had turns after it; a motion command is settled
//                        too by any later motion command the vehicle took (a lost take-off
//                        followed by an accepted leg: the vehicle did take off).
// An episode that failed with such a fault is counted as an agent-caused failure in a sweep.
#pragma once

#include <nlohmann/json.hpp>

namespace a3::rigs {

// [{"kind", "turn", "detail"}], in dialogue order; empty when the agent made none.
// `dialogue` is the episode's dialogue (turns with speaker, actions and obs).
nlohmann::json find_agent_faults(const nlohmann::json& dialogue);

}  // namespace a3::rigs
