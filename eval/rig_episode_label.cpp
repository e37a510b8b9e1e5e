// Who flew an a3rig episode, read with simdjson's DOM parser: the whole text is validated
// before any field is looked at, so a damaged file is refused as a whole (the on-demand
// API leaves a document unusable after an error inside it, which the episode fuzz target found).
#include "eval/rig_episode_label.hpp"

#include <simdjson.h>

namespace a3::eval {
namespace {

// Larger files are not a3rig's (its episodes are a few MB at most): not read, the check says why.
constexpr std::size_t kMaxLabelFileBytes = 64u << 20;

std::string string_field(const simdjson::dom::object& object, const char* key) {
  std::string_view value;
  if (object.at_key(key).get_string().get(value) != simdjson::SUCCESS) return "";
  return std::string(value);
}

std::optional<RigEpisodeLabel> label_of(const simdjson::padded_string& text) {
  simdjson::dom::parser parser;
  simdjson::dom::element document;
  if (parser.parse(text).get(document) != simdjson::SUCCESS) return std::nullopt;
  simdjson::dom::object meta, rig;
  if (document["_meta"].get_object().get(meta) != simdjson::SUCCESS) return std::nullopt;
  if (document["_rig"].get_object().get(rig) != simdjson::SUCCESS) return std::nullopt;
  RigEpisodeLabel label;
  label.model = string_field(meta, "model");
  label.scenario = string_field(rig, "scenario");
  if (rig["seed"].get_int64().get(label.seed) != simdjson::SUCCESS) label.seed = 0;
  const std::string think_time = string_field(rig, "think_time");
  const std::string slice = string_field(rig, "slice");
  if (label.model.empty() || label.scenario.empty()) return std::nullopt;
  if (!think_time.empty() && think_time != "0") label.model += ", think " + think_time;
  if (!slice.empty()) label.model += ", " + slice;
  return label;
}

}  // namespace

std::optional<RigEpisodeLabel> read_rig_episode_label(const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxLabelFileBytes || !std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  simdjson::padded_string text;
  if (simdjson::padded_string::load(path.string()).get(text) != simdjson::SUCCESS) return std::nullopt;
  return label_of(text);
}

std::optional<RigEpisodeLabel> rig_episode_label_from_text(std::string_view text) {
  return label_of(simdjson::padded_string(text));
}

}  // namespace a3::eval
