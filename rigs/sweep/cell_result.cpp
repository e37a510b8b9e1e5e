// Completeness of a cell's episode and its scores.
#include "rigs/sweep/cell_result.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include "common/json_text.hpp"

#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/json_shape.hpp"
#include "eval/pillars.hpp"

namespace a3::rigs::sweep {

CellCheck check_cell(const std::filesystem::path& dir, const SweepCell& cell) {
  CellCheck check;
  const auto path = dir / "episode.json";
  std::ifstream in(path);
  if (!in) {
    check.why_not = "no episode.json";
    return check;
  }
  std::ostringstream file_text;
  file_text << in.rdbuf();
  check.episode = common::try_parse_json_text(file_text.str(), nullptr, eval::episode_json_limits()).value_or(nlohmann::json());
  if (!check.episode.is_object()) {
    check.why_not = "episode.json is not a JSON object (half-written?)";
    return check;
  }
  static const nlohmann::json kNoRig = nlohmann::json::object();
  const nlohmann::json& rig =
      check.episode.contains("_rig") && check.episode["_rig"].is_object() ? check.episode["_rig"] : kNoRig;
  const auto text = [&](const char* key) {
    return rig.contains(key) && rig[key].is_string() ? rig[key].get<std::string>() : std::string("?");
  };
  const std::string status = text("status");
  if (status == "?") {
    check.why_not = "episode.json has no _rig.status (not written by a3rig run)";
    return check;
  }
  if (status == "interrupted" || status.rfind("node_failed", 0) == 0 || status.rfind("realtime_violated", 0) == 0 ||
      status.rfind("agent_failed", 0) == 0 || status.rfind("endpoint_failed", 0) == 0) {
    check.why_not = "the run ended " + status;
    check.realtime_violated = status.rfind("realtime_violated", 0) == 0;
    return check;
  }
  const bool seed_matches = rig.contains("seed") && rig["seed"].is_number_unsigned() &&
                            rig["seed"].get<uint64_t>() == cell.seed;
  if (text("agent") != cell.agent || text("think_time") != cell.think_time || !seed_matches) {
    check.why_not = "episode.json is of another cell (agent " + text("agent") + ", think time " +
                    text("think_time") + ", seed " + (rig.contains("seed") ? rig["seed"].dump() : "?") + ")";
    return check;
  }
  check.complete = true;
  return check;
}

struct EpisodeScorer::Impl {
  eval::JsonSchemaValidator validator{eval::episode_schema_json(), eval::kEpisodeSchemaName};
  eval::ScoringProfile profile = eval::release_profile();
  eval::EpisodeReader reader{validator, profile};
};

EpisodeScorer::EpisodeScorer() : impl_(std::make_unique<Impl>()) {}
EpisodeScorer::~EpisodeScorer() = default;

namespace {

ResultRow keyed_row(const SweepCell& cell) {
  ResultRow r;
  r.scenario = cell.scenario;
  r.agent = cell.agent;
  r.think_time = cell.think_time;
  r.think_time_mean_s = cell.think_time_mean_s;
  r.slice = cell.slice;
  r.seed = cell.seed;
  return r;
}

double number_at(const nlohmann::json& j, const char* pointer) {
  const nlohmann::json::json_pointer p(pointer);
  return j.contains(p) && j[p].is_number() ? j[p].get<double>() : std::nan("");
}

// The kinds of the episode's _rig.agent_faults, sorted and unique, ";"-joined.
std::string agent_fault_kinds(const nlohmann::json& episode) {
  const nlohmann::json::json_pointer p("/_rig/agent_faults");
  std::set<std::string> kinds;
  if (episode.contains(p) && episode[p].is_array()) {
    for (const auto& fault : episode[p]) {
      if (fault.is_object() && fault.contains("kind") && fault["kind"].is_string()) kinds.insert(fault["kind"].get<std::string>());
    }
  }
  std::string joined;
  for (const auto& k : kinds) joined += (joined.empty() ? "" : ";") + k;
  return joined;
}

}  // namespace

ResultRow EpisodeScorer::row(const SweepCell& cell, const nlohmann::json& episode, const std::string& episode_relative) {
  ResultRow r = keyed_row(cell);
  r.has_episode = true;
  r.status = episode["_rig"]["status"].get<std::string>();
  r.success = episode.contains("success") && episode["success"].is_boolean() && episode["success"].get<bool>();
  r.mission_time_s = number_at(episode, "/_rig/mission_time_s");
  r.wall_time_s = number_at(episode, "/_rig/wall_time_s");
  r.episode = episode_relative;
  r.agent_faults = agent_fault_kinds(episode);
  const eval::EpisodeCheck check = impl_->reader.check_text(episode.dump());
  r.valid = check.status == eval::EpisodeStatus::kValid;
  if (r.valid) {
    const eval::Pillars p = eval::score_pillars(check.facts, impl_->profile, impl_->profile.optimal_turns);
    r.alpha3 = p.alpha3;
    r.to = p.to;
    r.sp = p.sp;
    r.tc = p.tc;
    r.iq = p.iq;
    r.nr = p.nr;
    r.cc = p.cc;
  }
  return r;
}

ResultRow row_without_episode(const SweepCell& cell, const std::string& status) {
  ResultRow r = keyed_row(cell);
  r.status = status;
  return r;
}

}  // namespace a3::rigs::sweep
