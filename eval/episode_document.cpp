// Semantic rules and fact extraction on a parsed episode.
#include "eval/episode_document.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <string_view>

namespace a3::eval {
namespace {

using rapidjson::Value;

// The first member named key (as RapidJSON's FindMember). Always inlined: with a literal key
// the length is a constant and the comparison compiles to a few loads instead of a call to
// memcmp (these lookups were a sixth of scoring's instructions).
[[gnu::always_inline]] inline const Value* member_named(const Value& object, const char* key,
                                                        std::size_t length) {
  if (!object.IsObject()) return nullptr;
  for (auto it = object.MemberBegin(); it != object.MemberEnd(); ++it) {
    if (it->name.GetStringLength() == length && std::memcmp(it->name.GetString(), key, length) == 0) {
      return &it->value;
    }
  }
  return nullptr;
}

template <std::size_t N>
const Value* member(const Value& object, const char (&key)[N]) {
  return member_named(object, key, N - 1);
}

const Value* member(const Value& object, std::string_view key) {
  return member_named(object, key.data(), key.size());
}

std::string_view string_of(const Value* v) {
  if (v == nullptr || !v->IsString()) return {};
  return {v->GetString(), v->GetStringLength()};
}

double number_of(const Value* v, double fallback) {
  return v != nullptr && v->IsNumber() ? v->GetDouble() : fallback;
}

bool true_of(const Value* v) { return v != nullptr && v->IsBool() && v->GetBool(); }

bool is_mcp(const Value& action) { return string_of(member(action, "type")) == "mcp"; }

// An observation refers to an action when it names the action's tool (MCP) or task (A2A).
bool refers_to(const Value& observation, const Value& action) {
  if (is_mcp(action)) {
    const Value* tool = member(observation, "tool");
    return tool != nullptr && tool->IsString() && string_of(tool) == string_of(member(action, "name"));
  }
  const Value* task = member(observation, "task");
  return task != nullptr && task->IsString() && string_of(task) == string_of(member(action, "task"));
}

// TC's stricter match: an A2A answer must also carry from, status and payload.
bool answers(const Value& observation, const Value& action) {
  if (!refers_to(observation, action)) return false;
  if (is_mcp(action)) return true;
  return member(observation, "from") != nullptr && member(observation, "status") != nullptr &&
         member(observation, "payload") != nullptr;
}

const Value& array_or_empty(const Value* v) {
  static const Value kEmpty(rapidjson::kArrayType);
  return v != nullptr && v->IsArray() ? *v : kEmpty;
}

const Value* initial_pose(const Value& document) {
  const Value* initial = member(document, "initial_state");
  const Value* uav = initial != nullptr ? member(*initial, "uav") : nullptr;
  return uav != nullptr ? member(*uav, "pose") : nullptr;
}

std::string turn_path(rapidjson::SizeType i) { return "/dialogue/" + std::to_string(i); }

}  // namespace

bool is_failure_stub(const rapidjson::Value& document) {
  const Value* meta = member(document, "_meta");
  return meta != nullptr && true_of(member(*meta, "generation_failed"));
}

int64_t attempts_used_or_one(const rapidjson::Value& document) {
  const Value* meta = member(document, "_meta");
  const Value* attempts = meta != nullptr ? member(*meta, "attempts_used") : nullptr;
  if (attempts == nullptr || !attempts->IsNumber()) return 1;
  if (attempts->IsInt64()) return std::max<int64_t>(attempts->GetInt64(), 1);
  // 2.0 is an integer for JSON Schema 2020-12 and for the schema's multipleOf 1.
  const double value = attempts->GetDouble();
  if (value >= 1.0 && value < 9.0e18 && std::floor(value) == value) return static_cast<int64_t>(value);
  return 1;
}

Violations check_semantics(const rapidjson::Value& document, const ScoringProfile& profile) {
  Violations out;
  if (is_failure_stub(document)) return out;
  const Value& dialogue = array_or_empty(member(document, "dialogue"));
  const auto turns = static_cast<int>(dialogue.Size());
  if (turns < profile.min_turns || turns > profile.max_turns) {
    out.push_back({"/dialogue", "turn-count",
                   "the dialogue has " + std::to_string(turns) + " turns; an episode needs " +
                       std::to_string(profile.min_turns) + " to " +
                       std::to_string(profile.max_turns)});
  }
  std::string_view previous;
  for (rapidjson::SizeType i = 0; i < dialogue.Size(); ++i) {
    const Value& turn = dialogue[i];
    const std::string_view speaker = string_of(member(turn, "speaker"));
    if (speaker != "agent" && speaker != "user") {
      out.push_back({turn_path(i) + "/speaker", "role",
                     "speaker '" + std::string(speaker) + "' is not agent or user"});
    } else if (speaker == previous) {
      out.push_back({turn_path(i) + "/speaker", "alternation",
                     "speaker '" + std::string(speaker) + "' speaks twice in a row"});
    }
    previous = speaker;

    const Value& actions = array_or_empty(member(turn, "actions"));
    const Value& observations = array_or_empty(member(turn, "obs"));
    for (rapidjson::SizeType k = 0; k < observations.Size(); ++k) {
      if (member(observations[k], "tool") == nullptr && member(observations[k], "task") == nullptr) {
        out.push_back({turn_path(i) + "/obs/" + std::to_string(k), "observation-fields",
                       "an observation must name the tool (MCP) or the task (A2A) it answers"});
      }
    }
    for (rapidjson::SizeType j = 0; j < actions.Size(); ++j) {
      const Value& action = actions[j];
      const std::string path = turn_path(i) + "/actions/" + std::to_string(j);
      const bool mcp = is_mcp(action);
      static constexpr const char* kMcpFields[] = {"name", "args", nullptr};
      static constexpr const char* kA2aFields[] = {"task", "to", "payload", nullptr};
      std::string missing;
      for (const char* const* key = mcp ? kMcpFields : kA2aFields; *key != nullptr; ++key) {
        if (member(action, *key) == nullptr) missing += (missing.empty() ? "" : ", ") + std::string(*key);
      }
      if (!missing.empty()) {
        out.push_back({path, "action-fields",
                       std::string(mcp ? "MCP" : "A2A") + " action lacks " + missing});
        continue;
      }
      bool answered = false;
      for (const Value& observation : observations.GetArray()) {
        if (refers_to(observation, action)) {
          answered = true;
          break;
        }
      }
      if (!answered) {
        out.push_back({path, "unanswered-action",
                       mcp ? "no observation of this turn has tool '" +
                                 std::string(string_of(member(action, "name"))) + "'"
                           : "no observation of this turn has task '" +
                                 std::string(string_of(member(action, "task"))) + "'"});
      }
    }
  }
  return out;
}

EpisodeFacts extract_facts(const rapidjson::Value& document) {
  EpisodeFacts facts;
  facts.success = true_of(member(document, "success"));

  const Value& dialogue = array_or_empty(member(document, "dialogue"));
  facts.turns.reserve(dialogue.Size());
  for (const Value& turn : dialogue.GetArray()) {
    TurnFacts t;
    const std::string_view speaker = string_of(member(turn, "speaker"));
    t.speaker = speaker == "agent" ? Speaker::kAgent
                : speaker == "user" ? Speaker::kUser
                                    : Speaker::kOther;
    const Value& actions = array_or_empty(member(turn, "actions"));
    const Value& observations = array_or_empty(member(turn, "obs"));
    t.structured_actions = static_cast<int>(actions.Size());
    t.observations = static_cast<int>(observations.Size());
    for (const Value& action : actions.GetArray()) {
      for (const Value& observation : observations.GetArray()) {
        if (answers(observation, action)) {
          ++t.matched_actions;
          break;
        }
      }
    }
    if (const Value* net = member(turn, "net"); net != nullptr) {
      t.slice = std::string(string_of(member(*net, "slice")));
      t.lat_ms = number_of(member(*net, "lat_ms"), 0.0);
      t.loss_pct = number_of(member(*net, "loss_pct"), 0.0);
      t.throughput_mbps = number_of(member(*net, "throughput_mbps"), 0.0);
      t.edge_load = number_of(member(*net, "edge_load"), 0.0);
    }
    facts.turns.push_back(std::move(t));
  }

  if (const Value* home = initial_pose(document); home != nullptr) {
    const Value* x = member(*home, "x");
    const Value* y = member(*home, "y");
    facts.has_home = x != nullptr && x->IsNumber() && y != nullptr && y->IsNumber();
    facts.home_x_m = number_of(x, 0.0);
    facts.home_y_m = number_of(y, 0.0);
  }
  if (const Value* final_state = member(document, "final_state"); final_state != nullptr) {
    if (const Value* uav = member(*final_state, "uav"); uav != nullptr) {
      if (const Value* pose = member(*uav, "pose"); pose != nullptr) {
        facts.final_x_m = number_of(member(*pose, "x"), 0.0);
        facts.final_y_m = number_of(member(*pose, "y"), 0.0);
        facts.final_z_m = number_of(member(*pose, "z"), 0.0);
      }
      if (const Value* landed = member(*uav, "landed"); landed != nullptr) {
        facts.claims_landed_at_home = string_of(member(*landed, "site")) == "home";
      }
      if (const Value* energy = member(*uav, "energy"); energy != nullptr) {
        facts.battery_pct = number_of(member(*energy, "battery_pct"), 100.0);
      }
    }
    if (const Value* airspace = member(*final_state, "airspace"); airspace != nullptr) {
      const Value* bounds = member(*airspace, "alt_bounds");
      if (bounds != nullptr && bounds->IsArray() && bounds->Size() >= 2) {
        facts.alt_min_m = number_of(&(*bounds)[0], 0.0);
        facts.alt_max_m = number_of(&(*bounds)[1], 0.0);
      }
    }
    if (const Value* flags = member(*final_state, "safety_flags"); flags != nullptr) {
      facts.nfz_violation = true_of(member(*flags, "nfz_violation"));
      facts.separation_breach = true_of(member(*flags, "separation_breach"));
    }
  }

  if (const Value* meta = member(document, "_meta"); meta != nullptr) {
    facts.gen_time_s = number_of(member(*meta, "gen_time_s"), 0.0);
    if (const Value* usage = member(*meta, "usage"); usage != nullptr) {
      facts.total_tokens = number_of(member(*usage, "total_tokens"), 0.0);
    }
  }
  facts.attempts_used = attempts_used_or_one(document);
  return facts;
}

}  // namespace a3::eval
