// The corpus responder: loading a recorded model folder, matching requests to its episodes,
// replaying them attempt by attempt.
#include "agent/model_server/corpus_responder.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <tuple>

#include "agent/llm/json_extract.hpp"
#include "common/json_text.hpp"
#include "episode/episode.hpp"

namespace a3::agent::model_server {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

constexpr int kStubAttempts = 3;  // a stub records that every attempt of the protocol failed

// sc-XXXX-ep-YY.json → (XXXX, YY).
std::optional<std::pair<int, int>> episode_numbers(const std::string& name) {
  int scenario = 0, episode = 0;
  char tail = 0;
  if (name.size() != 18 || std::sscanf(name.c_str(), "sc-%4d-ep-%2d.jso%c", &scenario, &episode, &tail) != 3 ||
      tail != 'n' || name.compare(0, 3, "sc-") != 0 || name.compare(7, 4, "-ep-") != 0) {
    return std::nullopt;
  }
  for (std::size_t i : {3u, 4u, 5u, 6u, 11u, 12u}) {
    if (!std::isdigit(static_cast<unsigned char>(name[i]))) return std::nullopt;
  }
  return std::make_pair(scenario, episode);
}

// A failure stub: the paper's seed of its file's episode index, the recorded error.
void read_stub(RecordedEpisode& e, const episode::EpisodeMeta& meta) {
  const auto seed = paper_episode_seed(e.episode_index);
  if (!seed) {
    throw std::invalid_argument(e.file + ": a failure stub (no _meta.seed) with episode index " +
                                std::to_string(e.episode_index) + " beyond the paper's five seeds");
  }
  e.seed = *seed;
  e.error = meta.error.value_or("generation failed");
  e.attempts_used = kStubAttempts;
}

// A recorded episode: its seed, generation time, attempts and usage, and its text without _meta.
void read_recorded(RecordedEpisode& e, const episode::Episode& episode, const episode::EpisodeMeta& meta) {
  if (!meta.seed) throw std::invalid_argument(e.file + ": _meta.seed missing");
  e.seed = *meta.seed;
  if (!meta.gen_time_s || *meta.gen_time_s < 0.0) {
    throw std::invalid_argument(e.file + ": _meta.gen_time_s missing or negative");
  }
  e.gen_time_s = *meta.gen_time_s;
  if (meta.attempts_used) {
    if (*meta.attempts_used < 1.0) throw std::invalid_argument(e.file + ": _meta.attempts_used must be a number >= 1");
    e.attempts_used = static_cast<int>(*meta.attempts_used);
  }
  if (!meta.usage) throw std::invalid_argument(e.file + ": _meta.usage missing");
  e.usage = *meta.usage;
  e.content = episode.without_meta().dump(-1, ' ', false, ordered_json::error_handler_t::replace);
}

RecordedEpisode recorded_episode(const episode::Episode& episode, int scenario, int episode_index) {
  const episode::EpisodeMeta meta = episode.meta();
  if (!meta.present) throw std::invalid_argument(episode.where() + ": no _meta object");
  const episode::Document* initial_state = episode.initial_state();
  if (initial_state == nullptr) throw std::invalid_argument(episode.where() + ": no initial_state object");
  RecordedEpisode e;
  e.file = episode.where();
  e.scenario = scenario;
  e.episode_index = episode_index;
  e.generation_failed = meta.generation_failed;
  e.initial_state = canonical_initial_state(json(*initial_state));
  if (e.generation_failed) {
    read_stub(e, meta);
  } else {
    read_recorded(e, episode, meta);
  }
  return e;
}

RecordedEpisode read_episode(const fs::path& path, int scenario, int episode_index) {
  try {
    return recorded_episode(episode::Episode::load(path), scenario, episode_index);
  } catch (const common::InputError& e) {
    throw std::invalid_argument(e.what());
  }
}

// The value after `label` on the last line of the system and user messages that carries it.
std::optional<std::string> tag_value(const json& request, const std::string& label) {
  std::optional<std::string> found;
  if (!request.contains("messages") || !request["messages"].is_array()) return found;
  for (const auto& m : request["messages"]) {
    if (!m.is_object() || !m.contains("content") || !m["content"].is_string()) continue;
    const std::string role = m.value("role", "");
    if (role != "user" && role != "system") continue;
    const std::string& text = m["content"].get_ref<const std::string&>();
    for (std::size_t pos = text.find(label); pos != std::string::npos; pos = text.find(label, pos + 1)) {
      if (pos != 0 && text[pos - 1] != '\n') continue;  // a tag starts a line
      std::size_t begin = pos + label.size();
      const std::size_t end = std::min(text.find('\n', begin), text.size());
      while (begin < end && std::isspace(static_cast<unsigned char>(text[begin]))) ++begin;
      std::size_t stop = end;
      while (stop > begin && std::isspace(static_cast<unsigned char>(text[stop - 1]))) --stop;
      found = text.substr(begin, stop - begin);
    }
  }
  return found;
}

int64_t parse_integer(const std::string& text, const std::string& what) {
  std::size_t used = 0;
  int64_t value = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0) throw std::invalid_argument(what + " '" + text + "' is not an integer");
  return value;
}

std::string seeds_of(const std::vector<std::size_t>& indices, const std::vector<RecordedEpisode>& episodes) {
  std::string out;
  for (std::size_t i : indices) out += (out.empty() ? "" : ", ") + std::to_string(episodes[i].seed);
  return out;
}

// `total` split over `parts` shares: the share of part `index` (0-based), remainder on the last.
int64_t share(int64_t total, int parts, int index) {
  const int64_t each = total / parts;
  return index + 1 < parts ? each : total - each * (parts - 1);
}

}  // namespace

std::optional<int64_t> paper_episode_seed(int episode_index) {
  static constexpr int64_t kSeeds[] = {42, 77, 101, 2025, 1337};
  if (episode_index < 0 || episode_index >= 5) return std::nullopt;
  return kSeeds[episode_index];
}

std::string canonical_initial_state(const json& initial_state) { return initial_state.dump(); }

CorpusRequestTags read_corpus_request_tags(const json& request) {
  CorpusRequestTags tags;
  if (const auto id = tag_value(request, "scenario_id:")) {
    std::string digits = *id;
    if (digits.rfind("sc-", 0) == 0) digits = digits.substr(3);
    const int64_t n = parse_integer(digits, "scenario_id");
    if (n < 0 || n > 9999) throw std::invalid_argument("scenario_id '" + *id + "' is not sc-0000..sc-9999");
    tags.scenario = static_cast<int>(n);
  }
  if (const auto seed = tag_value(request, "episode_seed:")) tags.seed = parse_integer(*seed, "episode_seed");
  if (const auto attempt = tag_value(request, "attempt:")) {
    const int64_t n = parse_integer(*attempt, "attempt");
    if (n < 1 || n > 100) throw std::invalid_argument("attempt '" + *attempt + "' must be 1..100");
    tags.attempt = static_cast<int>(n);
  }
  return tags;
}

CorpusResponder::CorpusResponder(std::vector<RecordedEpisode> episodes) : episodes_(std::move(episodes)) {
  if (episodes_.empty()) throw std::invalid_argument("corpus responder: no recorded episode");
  std::sort(episodes_.begin(), episodes_.end(), [](const RecordedEpisode& a, const RecordedEpisode& b) {
    return std::tie(a.scenario, a.episode_index) < std::tie(b.scenario, b.episode_index);
  });
  for (std::size_t i = 0; i < episodes_.size(); ++i) {
    by_scenario_[episodes_[i].scenario].push_back(i);
    scenario_by_initial_state_.emplace(episodes_[i].initial_state, episodes_[i].scenario);
  }
}

std::size_t CorpusResponder::failure_stub_count() const {
  return static_cast<std::size_t>(std::count_if(episodes_.begin(), episodes_.end(),
                                                [](const RecordedEpisode& e) { return e.generation_failed; }));
}

const RecordedEpisode& CorpusResponder::match(const json& request, CorpusRequestTags* tags_out) const {
  const CorpusRequestTags tags = read_corpus_request_tags(request);
  if (tags_out != nullptr) *tags_out = tags;
  std::optional<int> scenario = tags.scenario;
  if (!scenario) {
    // No id: the first JSON object of the user messages that is (or holds) a recorded initial_state.
    for (const auto& m : request.value("messages", json::array())) {
      if (scenario || !m.is_object() || m.value("role", "") != "user" || !m.contains("content") ||
          !m["content"].is_string()) {
        continue;
      }
      const std::string& text = m["content"].get_ref<const std::string&>();
      for (const auto& span : llm::top_level_object_spans(text)) {
        if (!span.closed) continue;
        // A client's text: bounded depth before canonical_initial_state walks it.
        const json object =
            common::try_parse_json_text(std::string_view(text).substr(span.begin, span.end - span.begin)).value_or(json());
        if (!object.is_object()) continue;
        const json& state = object.contains("initial_state") ? object["initial_state"] : object;
        if (const auto known = scenario_by_initial_state_.find(canonical_initial_state(state));
            known != scenario_by_initial_state_.end()) {
          scenario = known->second;
          break;
        }
      }
    }
    if (!scenario) {
      throw std::invalid_argument(
          "corpus responder: the request names no scenario (a line 'scenario_id: sc-XXXX') and carries no "
          "initial_state recorded in this corpus");
    }
  }
  const auto it = by_scenario_.find(*scenario);
  if (it == by_scenario_.end()) {
    char id[16];
    std::snprintf(id, sizeof id, "sc-%04d", *scenario);
    throw std::invalid_argument(std::string("corpus responder: the corpus has no episode of scenario ") + id);
  }
  if (!tags.seed) return episodes_[it->second.front()];
  for (std::size_t i : it->second) {
    if (episodes_[i].seed == *tags.seed) return episodes_[i];
  }
  char id[16];
  std::snprintf(id, sizeof id, "sc-%04d", *scenario);
  throw std::invalid_argument(std::string("corpus responder: the corpus has no episode of scenario ") + id +
                              " with episode_seed " + std::to_string(*tags.seed) + " (it has seed(s) " +
                              seeds_of(it->second, episodes_) + ")");
}

ResponderReply CorpusResponder::respond(const json& request) {
  CorpusRequestTags tags;
  const RecordedEpisode& e = match(request, &tags);
  ResponderReply reply;
  if (e.generation_failed) {
    reply.content = "(a3rig corpus replay of " + fs::path(e.file).filename().string() +
                    ": this generation failed when recorded) " + e.error;
    reply.usage = {{"prompt_tokens", 0}, {"completion_tokens", 0}, {"total_tokens", 0}};
    return reply;
  }
  const int k = e.attempts_used;
  const int index = std::min(tags.attempt, k) - 1;  // attempts beyond k replay the episode again
  reply.latency_s = e.gen_time_s / k;
  if (index + 1 < k) {
    reply.content = "(a3rig corpus replay of " + fs::path(e.file).filename().string() + ": attempt " +
                    std::to_string(tags.attempt) + " of the recorded " + std::to_string(k) +
                    " failed validation when recorded)";
    reply.usage = json::object();
  } else {
    reply.content = e.content;
    reply.usage = e.usage;
  }
  for (const char* key : {"prompt_tokens", "completion_tokens", "total_tokens"}) {
    reply.usage[key] = share(episode::usage_count(e.usage, key), k, index);
  }
  return reply;
}

std::unique_ptr<CorpusResponder> make_corpus_responder(const CorpusResponderOptions& options) {
  if (options.folder.empty()) {
    throw std::invalid_argument("corpus responder: give --corpus DIR (a model's folder, e.g. "
                                "eval_runs/openai/chatgpt-4o-latest/uav)");
  }
  const fs::path folder(options.folder);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    throw std::invalid_argument("--corpus " + options.folder + ": not a folder");
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    if (entry.is_regular_file() && episode_numbers(entry.path().filename().string())) files.push_back(entry.path());
  }
  if (ec) throw std::invalid_argument("--corpus " + options.folder + ": cannot list (" + ec.message() + ")");
  if (files.empty()) {
    throw std::invalid_argument("--corpus " + options.folder +
                                ": no sc-XXXX-ep-YY.json file (give a model's domain folder, e.g. "
                                "eval_runs/openai/chatgpt-4o-latest/uav)");
  }
  std::sort(files.begin(), files.end());
  std::vector<RecordedEpisode> episodes;
  for (const auto& path : files) {
    const auto numbers = episode_numbers(path.filename().string());
    episodes.push_back(read_episode(path, numbers->first, numbers->second));
  }
  return std::make_unique<CorpusResponder>(std::move(episodes));
}

}  // namespace a3::agent::model_server
