// One α³-Bench episode document (SPEC-alpha3.md §1), parsed once, with typed access to what the
// rig's readers need: the dialogue and its turns (speaker, actions, the 6G vector n_t), `_meta`
// and `_rig`. Replay, trace replay, the corpus responder, the report and the resume of
// `a3rig generate` read episodes through it. Keys keep the recorded order (ordered_json), so an
// episode replayed as text reads as it was written.
//
// Scoring reads episode files on its own path (eval/: RapidJSON and the compiled JSON Schema,
// tens of thousands of episodes a second), where a malformed file is a scored violation, not an
// error; here a malformed field is an InputError naming the file and the JSON path.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "episode/episode_meta.hpp"

namespace a3::episode {

using Document = nlohmann::ordered_json;

// The largest episode file read (the corpus's largest is about 40 KiB).
inline constexpr std::uintmax_t kMaxEpisodeBytes = std::uintmax_t{16} << 20;

class Episode {
 public:
  // Reads and parses an episode file. Throws common::InputError naming the file.
  static Episode load(const std::filesystem::path& file);
  // Parses episode text; `where` names it in errors (a file name, "episode").
  static Episode parse(std::string_view text, const std::string& where);
  // Throws common::InputError unless `document` is an object with a "dialogue" array.
  Episode(Document document, std::string where);

  const std::string& where() const { return where_; }
  const Document& document() const { return document_; }

  // The dialogue's turns, in order; turn(i) is the i-th object ("<where>: /dialogue/<i>" in errors).
  std::size_t turn_count() const { return dialogue().size(); }
  const Document& turn(std::size_t i) const;
  std::string turn_where(std::size_t i) const;
  // The turn's "speaker" (InputError when it is absent or not a string).
  std::string speaker(std::size_t i) const;
  // The indices of the turns `speaker` spoke, in order.
  std::vector<std::size_t> turns_of(std::string_view speaker) const;
  // The turn's "actions" array (InputError when absent or not an array).
  const Document& actions(std::size_t i) const;
  // The turn's 6G vector "net" (InputError when absent or not an object).
  const Document& net(std::size_t i) const;

  // `_meta`, typed (an absent `_meta` gives EpisodeMeta{} with present == false).
  EpisodeMeta meta() const;
  // `_rig` when the episode has it as an object (episodes the rig flew), else nullptr.
  const Document* rig() const;
  // `initial_state` when it is an object, else nullptr.
  const Document* initial_state() const;
  // The document without `_meta` (what a model wrote, for replaying it as a reply).
  Document without_meta() const;

 private:
  const Document& dialogue() const { return document_["dialogue"]; }

  Document document_;
  std::string where_;
};

}  // namespace a3::episode
