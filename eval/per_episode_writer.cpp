// Per-episode rows.
#include "eval/per_episode_writer.hpp"

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <vector>

#include "common/csv_text.hpp"
#include "common/json_text.hpp"
#include "eval/leaderboard_format.hpp"

namespace a3::eval {
namespace {

const std::vector<std::string>& columns() {
  static const std::vector<std::string> kColumns = {
      "model", "domain", "file", "scenario", "episode", "status", "error",
      "TO", "SP", "TC", "IQ", "NR", "CC", "alpha3",
      "success", "turns", "agent_turns", "agent_turns_with_obs", "alternation_ok",
      "structured_actions", "matched_actions", "hard_turns", "hard_actions", "normal_actions",
      "hard_embb_turns", "nr_base", "nr_adapt", "nr_slice", "nr_bonus",
      "V_alt", "V_nfz", "V_sep", "V_batt", "final_z_m", "alt_min_m", "alt_max_m", "battery_pct",
      "total_tokens", "gen_time_s", "attempts_used", "t_opt"};
  return kColumns;
}

nlohmann::ordered_json row(const ScoredEpisode& e) {
  nlohmann::ordered_json j;
  j["model"] = e.file.model;
  j["domain"] = e.file.domain;
  j["file"] = e.file.path.string();
  j["scenario"] = e.file.name ? nlohmann::ordered_json(e.file.name->scenario) : nullptr;
  j["episode"] = e.file.name ? nlohmann::ordered_json(e.file.name->episode) : nullptr;
  j["status"] = to_string(e.check.status);
  std::string error;
  for (const auto& v : e.check.violations) error += (error.empty() ? "" : "; ") + to_string(v);
  j["error"] = error;
  if (e.pillars == nullptr) {
    for (std::size_t c = 7; c < columns().size(); ++c) j[columns()[c]] = nullptr;
    j["attempts_used"] = e.check.attempts_used;
    return j;
  }
  const Pillars& p = *e.pillars;
  const PillarInputs& in = p.inputs;
  const EpisodeFacts& f = e.check.facts;
  j["TO"] = p.to;
  j["SP"] = p.sp;
  j["TC"] = p.tc;
  j["IQ"] = p.iq;
  j["NR"] = p.nr;
  j["CC"] = p.cc;
  j["alpha3"] = p.alpha3;
  j["success"] = f.success;
  j["turns"] = in.turns;
  j["agent_turns"] = in.agent_turns;
  j["agent_turns_with_obs"] = in.agent_turns_with_obs;
  j["alternation_ok"] = in.alternation_ok;
  j["structured_actions"] = in.structured_actions;
  j["matched_actions"] = in.matched_actions;
  j["hard_turns"] = in.hard_turns;
  j["hard_actions"] = in.hard_actions;
  j["normal_actions"] = in.normal_actions;
  j["hard_embb_turns"] = in.hard_penalised_slice_turns;
  j["nr_base"] = in.nr_base;
  j["nr_adapt"] = in.nr_adapt;
  j["nr_slice"] = in.nr_slice;
  j["nr_bonus"] = in.nr_bonus;
  j["V_alt"] = in.v_alt;
  j["V_nfz"] = in.v_nfz;
  j["V_sep"] = in.v_sep;
  j["V_batt"] = in.v_batt;
  j["final_z_m"] = f.final_z_m;
  j["alt_min_m"] = f.alt_min_m;
  j["alt_max_m"] = f.alt_max_m;
  j["battery_pct"] = f.battery_pct;
  j["total_tokens"] = f.total_tokens;
  j["gen_time_s"] = f.gen_time_s;
  j["attempts_used"] = f.attempts_used;
  j["t_opt"] = in.optimal_turns;
  return j;
}

std::string csv_value(const nlohmann::ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return common::csv_cell(v.get<std::string>());
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_float()) return format_double(v.get<double>());
  return common::dump_json_text(v);
}

}  // namespace

PerEpisodeWriter::PerEpisodeWriter(const std::filesystem::path& path) : out_(path) {
  json_lines_ = path.extension() == ".jsonl";
  if (!json_lines_) {
    for (std::size_t c = 0; c < columns().size(); ++c) pending_ += (c ? "," : "") + columns()[c];
    pending_ += "\n";
  }
}

void PerEpisodeWriter::flush_when_full() {
  constexpr std::size_t kChunkBytes = 64 * 1024;
  if (pending_.size() < kChunkBytes) return;
  out_.write(pending_);
  pending_.clear();
}

void PerEpisodeWriter::write(const ScoredEpisode& episode) {
  const auto j = row(episode);
  if (json_lines_) {
    pending_ += common::dump_json_text(j) + "\n";
  } else {
    std::size_t c = 0;
    for (const auto& name : columns()) pending_ += (c++ ? "," : "") + csv_value(j[name]);
    pending_ += "\n";
  }
  flush_when_full();
}

void PerEpisodeWriter::close() {
  out_.write(pending_);
  pending_.clear();
  out_.commit();
}

}  // namespace a3::eval
