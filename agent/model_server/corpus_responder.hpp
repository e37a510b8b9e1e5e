// The "corpus" responder of `a3rig serve-model`: replays a recorded α³-Bench model folder
// (<provider>/<model>/<domain>/ with sc-XXXX-ep-YY.json files) to `a3rig generate`, so that the
// paper's offline protocol runs without a network and reproduces the recorded leaderboard row.
//
// A request names its scenario and episode seed in the lines `a3rig generate` writes into its
// user message (rigs/generate/generate_prompt.hpp):
//   scenario_id: sc-0013      the scenario number (else: the first JSON object of the user
//                             messages, or its "initial_state", equal to a recorded initial_state)
//   episode_seed: 42          the seed (absent: any recorded seed of the scenario)
//   attempt: 2 of 3           the generation attempt (absent: 1)
// The answer is the recorded episode (everything but `_meta`, keys in the recorded order), with
// the recorded `_meta.gen_time_s` as latency and `_meta.usage` as usage. An episode recorded as
// needing k attempts is answered, for attempts 1..k-1, with a reply that is not JSON (so the
// client's validation fails as it did then), and with the episode at attempt k; the latency and
// the token counts (prompt, completion, total) are split evenly over the k attempts (remainders
// and the other usage fields, such as cost, go with attempt k), so that the sums are the recorded
// ones. A failure stub (generation_failed) is answered with a non-JSON reply at every attempt,
// quoting the recorded error, with no latency: the client fails all its attempts and writes a
// stub too.
//
// Seeds: a recorded episode's seed is its `_meta.seed`; a stub records none, so its seed is the
// paper's episode seed of its file's episode index (ep-00: 42, ep-01: 77, ep-02: 101,
// ep-03: 2025, ep-04: 1337). A request for a seed the folder has no episode of is refused
// (HTTP 400, naming the seeds it has).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "agent/model_server/model_responder.hpp"

namespace a3::agent::model_server {

// `a3rig serve-model --responder corpus` options.
struct CorpusResponderOptions {
  std::string folder;  // a model's domain folder, e.g. .../eval_runs/openai/chatgpt-4o-latest/uav
};

// One recorded episode file, as the responder replays it.
struct RecordedEpisode {
  std::string file;               // where it came from, for messages
  int scenario = -1;              // XXXX of sc-XXXX-ep-YY.json
  int episode_index = -1;         // YY
  int64_t seed = 0;               // _meta.seed, or the paper's seed of YY for a stub
  bool generation_failed = false; // a failure stub
  std::string error;              // a stub's recorded _meta.error
  std::string content;            // the episode without _meta, as the reply's content
  std::string initial_state;      // canonical_initial_state of its initial_state
  double gen_time_s = 0.0;        // _meta.gen_time_s (0 for a stub)
  int attempts_used = 1;          // _meta.attempts_used (3 for a stub: every attempt failed)
  nlohmann::json usage = nlohmann::json::object();  // _meta.usage
};

// What a request asks for, read from its messages (the tag lines above).
struct CorpusRequestTags {
  std::optional<int> scenario;
  std::optional<int64_t> seed;
  int attempt = 1;
};
// Reads the tags from the system and user messages' text. Throws std::invalid_argument for a
// tag that is present but malformed (names it).
CorpusRequestTags read_corpus_request_tags(const nlohmann::json& request);

// The paper's episode seed for episode index YY (0..4), or nothing beyond.
std::optional<int64_t> paper_episode_seed(int episode_index);

class CorpusResponder final : public ModelResponder {
 public:
  // Throws std::invalid_argument when there is no recorded episode.
  explicit CorpusResponder(std::vector<RecordedEpisode> episodes);
  std::string name() const override { return "corpus"; }
  // Throws std::invalid_argument (HTTP 400) naming what the request lacks: a scenario the folder
  // has, a recorded seed of it.
  ResponderReply respond(const nlohmann::json& request) override;

  std::size_t episode_count() const { return episodes_.size(); }
  std::size_t failure_stub_count() const;
  // The recorded episode a request would be answered from (for tests and messages).
  const RecordedEpisode& match(const nlohmann::json& request, CorpusRequestTags* tags = nullptr) const;

 private:
  std::vector<RecordedEpisode> episodes_;
  std::map<int, std::vector<std::size_t>> by_scenario_;      // scenario → episodes_ indices
  std::map<std::string, int> scenario_by_initial_state_;     // canonical initial_state → scenario
};

// Reads every sc-XXXX-ep-YY.json of `folder` (not recursively; other files are ignored). Throws
// std::invalid_argument naming the folder when it is missing or holds no episode file, and the
// file (and field) when one is not JSON or lacks what replay needs.
std::unique_ptr<CorpusResponder> make_corpus_responder(const CorpusResponderOptions& options);

// The canonical text of an initial_state (keys sorted, numbers as parsed), for matching.
std::string canonical_initial_state(const nlohmann::json& initial_state);

}  // namespace a3::agent::model_server
