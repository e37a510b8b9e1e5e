// Reading an episode document once and handing out its parts.
#include "episode/episode.hpp"

#include <fstream>
#include <sstream>

#include "common/json_text.hpp"

namespace a3::episode {
namespace {

using common::InputError;

std::string type_of(const Document& value) { return value.type_name(); }

// `value[key]`, which must exist and be of the kind `is_kind` tests; `where` is the value's own
// path ("ep.json: /dialogue/3"), `kind` what it must be ("an array").
const Document& require(const Document& value, const char* key, const std::string& where,
                        bool (Document::*is_kind)() const noexcept, const char* kind) {
  const auto it = value.find(key);
  if (it == value.end()) throw InputError(where + "/" + key + ": missing");
  if (!((*it).*is_kind)()) throw InputError(where + "/" + key + ": expected " + kind + ", got " + type_of(*it));
  return *it;
}

std::string read_text(const std::filesystem::path& file) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw InputError(file.string() + ": cannot read (" + ec.message() + ")");
  if (size > kMaxEpisodeBytes) throw InputError(file.string() + ": larger than 16 MiB, not an episode");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Episode Episode::load(const std::filesystem::path& file) { return parse(read_text(file), file.string()); }

Episode Episode::parse(std::string_view text, const std::string& where) {
  return Episode(common::parse_ordered_json_text(text, where, {kMaxEpisodeBytes, 128}), where);
}

Episode::Episode(Document document, std::string where) : document_(std::move(document)), where_(std::move(where)) {
  if (!document_.is_object()) throw InputError(where_ + ": an episode is a JSON object, got " + type_of(document_));
  require(document_, "dialogue", where_ + ": ", &Document::is_array, "an array");
}

const Document& Episode::turn(std::size_t i) const {
  const Document& t = dialogue().at(i);
  if (!t.is_object()) throw InputError(turn_where(i) + ": a turn is an object, got " + type_of(t));
  return t;
}

std::string Episode::turn_where(std::size_t i) const { return where_ + ": /dialogue/" + std::to_string(i); }

std::string Episode::speaker(std::size_t i) const {
  return require(turn(i), "speaker", turn_where(i), &Document::is_string, "a string").get<std::string>();
}

std::vector<std::size_t> Episode::turns_of(std::string_view who) const {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < turn_count(); ++i) {
    if (speaker(i) == who) indices.push_back(i);
  }
  return indices;
}

const Document& Episode::actions(std::size_t i) const {
  return require(turn(i), "actions", turn_where(i), &Document::is_array, "an array");
}

const Document& Episode::net(std::size_t i) const {
  return require(turn(i), "net", turn_where(i), &Document::is_object, "an object");
}

EpisodeMeta Episode::meta() const {
  const auto it = document_.find("_meta");
  if (it == document_.end()) return {};
  if (!it->is_object()) throw InputError(where_ + ": /_meta: expected an object, got " + type_of(*it));
  return read_episode_meta(*it, where_ + ": /_meta");
}

const Document* Episode::rig() const {
  const auto it = document_.find("_rig");
  return it != document_.end() && it->is_object() ? &*it : nullptr;
}

const Document* Episode::initial_state() const {
  const auto it = document_.find("initial_state");
  return it != document_.end() && it->is_object() ? &*it : nullptr;
}

Document Episode::without_meta() const {
  Document body = document_;
  body.erase("_meta");
  return body;
}

}  // namespace a3::episode
