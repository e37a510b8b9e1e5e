// Reading one parsed episode document (RapidJSON DOM): failure-stub recognition, the semantic
// rules JSON Schema cannot express (SPEC-alpha3.md §1), and extraction of the facts the pillars
// need. check_semantics() and extract_facts() expect a document that passed the schema.
#pragma once

#include "eval/rapidjson.hpp"

#include "eval/episode_facts.hpp"
#include "eval/scoring_profile.hpp"
#include "eval/violation.hpp"

namespace a3::eval {

// True when `_meta.generation_failed` is true: a failure stub, written when every generation
// attempt failed; it counts as a failure, not as an invalid file.
bool is_failure_stub(const rapidjson::Value& document);

// Rules (each violation names its rule):
//   turn-count          T outside [profile.min_turns, profile.max_turns]
//   role                a speaker other than "agent" or "user"
//   alternation         the same speaker twice in a row
//   action-fields       an MCP action without name/args, an A2A action without task/to/payload
//   observation-fields  an observation naming neither a tool nor a task
//   unanswered-action   an action with no observation of its turn naming its tool (MCP) or
//                       task (A2A)
Violations check_semantics(const rapidjson::Value& document, const ScoringProfile& profile);

// `_meta.attempts_used` when it is a positive integer, else 1 (SPEC §3: a stub counts 1).
int64_t attempts_used_or_one(const rapidjson::Value& document);

EpisodeFacts extract_facts(const rapidjson::Value& document);

}  // namespace a3::eval
