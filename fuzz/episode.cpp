// Fuzz target "episode": an episode file's text through the scorer's reader (UTF-8, JSON
// syntax, schema, failure stub, semantic checks, facts), then the α³ pillars of a valid one
// under both scoring profiles. Invariants: every pillar and α³ lie in [0, 1]; the compiled
// schema (what scoring validates with) and valijson give the same verdict on every document;
// the fast parser (simdjson) and the reference parser build the same document from every text
// simdjson accepts; the a3rig episode label (rig_episode_label) is read or refused, never crashes;
// the rig's episode model (episode/: what replay, trace replay and the report read) reads every
// part of the text or refuses it with an InputError, nothing else.
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "eval/compiled_schema.hpp"
#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/exact_numbers.hpp"
#include "eval/json_shape.hpp"
#include "eval/parser_agreement.hpp"
#include "eval/pillars.hpp"
#include "common/json_file.hpp"
#include "episode/episode.hpp"
#include "eval/rig_episode_label.hpp"
#include "fuzz/fuzz_target.hpp"

namespace {

void require_unit_interval(double x, const char* what) { a3::fuzz::require(x >= 0.0 && x <= 1.0, what); }

void score_both_profiles(const a3::eval::EpisodeFacts& facts) {
  for (const auto& profile : {a3::eval::release_profile(), a3::eval::paper_profile()}) {
    const a3::eval::Pillars p = a3::eval::score_pillars(facts, profile, profile.optimal_turns);
    require_unit_interval(p.to, "TO outside [0, 1]");
    require_unit_interval(p.sp, "SP outside [0, 1]");
    require_unit_interval(p.tc, "TC outside [0, 1]");
    require_unit_interval(p.iq, "IQ outside [0, 1]");
    require_unit_interval(p.nr, "NR outside [0, 1]");
    require_unit_interval(p.cc, "CC outside [0, 1]");
    require_unit_interval(p.alpha3, "alpha3 outside [0, 1]");
  }
}

// Parsed and depth-checked as the reader does, then validated by both.
void require_validators_agree(std::string_view text) {
  static const a3::eval::JsonSchemaValidator valijson(a3::eval::episode_schema_json(), a3::eval::kEpisodeSchemaName,
                                                      a3::eval::SchemaEngine::kValijson);
  static const a3::eval::CompiledSchema compiled(a3::eval::episode_schema_json(), a3::eval::kEpisodeSchemaName);
  static a3::eval::ExactNumberParser parser;
  static a3::eval::JsonShapeChecker shape;
  if (std::memchr(text.data(), '\0', text.size()) != nullptr) return;
  std::string buffer(text);
  rapidjson::Document document;
  if (parser.parse_insitu(document, buffer.data()).IsError()) return;
  a3::eval::Violations violations;
  if (shape.check(document, violations)) return;
  a3::fuzz::require(valijson.is_valid(document) == compiled.is_valid(document),
                    "the compiled schema and valijson disagree");
}

// Every part episode/ hands out, each read or refused on its own.
void read_every_part(std::string_view text) {
  std::optional<a3::episode::Episode> episode;
  try {
    episode.emplace(a3::episode::Episode::parse(text, "fuzz"));
  } catch (const a3::common::InputError&) {
    return;
  }
  const auto refused_or_read = [](auto&& read) {
    try {
      read();
    } catch (const a3::common::InputError&) {
    }
  };
  refused_or_read([&] { (void)episode->meta().usage_count("total_tokens"); });
  refused_or_read([&] { (void)episode->without_meta(); });
  (void)episode->rig();
  (void)episode->initial_state();
  for (std::size_t i = 0; i < episode->turn_count(); ++i) {
    refused_or_read([&] { (void)episode->speaker(i); });
    refused_or_read([&] { (void)episode->actions(i); });
    refused_or_read([&] { (void)episode->net(i); });
  }
}

}  // namespace

A3_FUZZ_TARGET(episode) {
  static const a3::eval::JsonSchemaValidator validator(a3::eval::episode_schema_json(), a3::eval::kEpisodeSchemaName);
  static const a3::eval::ScoringProfile profile = a3::eval::release_profile();
  static a3::eval::EpisodeReader reader(validator, profile);
  const std::string_view text(reinterpret_cast<const char*>(input.data()), input.size());
  require_validators_agree(text);
  a3::fuzz::require(!a3::eval::compare_parsers(text).disagreement, "simdjson and the reference parser disagree");
  const a3::eval::EpisodeCheck check = reader.check_text(text);
  if (check.status == a3::eval::EpisodeStatus::kValid) score_both_profiles(check.facts);
  a3::fuzz::require(check.status != a3::eval::EpisodeStatus::kInvalid || !check.violations.empty(),
                    "an invalid episode without a reason");
  read_every_part(text);
  // How `a3rig score` names a3rig's own episode.json: a label has both its parts, or none is given.
  if (const auto label = a3::eval::rig_episode_label_from_text(text)) {
    a3::fuzz::require(!label->model.empty() && !label->scenario.empty(), "a rig episode label with an empty part");
  }
}
