// How long `a3rig serve-model` waits before answering a chat-completions request. Specs:
//   "recorded"                      the responder's recorded latency (0 when it has none)
//   "2.5", "fixed:S", "uniform:A,B", "normal:MEAN,SD", "lognormal:MEDIAN,SIGMA", "exp:MEAN"
//                                   a distribution per request (the think-time forms,
//                                   agent/conversation/think_time.hpp)
//   "model:<name>"                  a model of the paper, per request as one agent turn: its
//                                   published mean generation time per episode spread over the
//                                   turns, as ThinkTime does (e.g. "model:GPT-4.1-mini")
//   "model-episode:<name>"          the same model, per request as one whole episode (the paper's
//                                   generation protocol: mean = the published gen_time_s)
//   "tokens:PREFILL,DECODE[,TTFT]"  from the reply's token counts: TTFT + prompt_tokens /
//                                   PREFILL + completion_tokens / DECODE (tokens per second)
// Every latency is multiplied by the time scale (e.g. 0.1: ten times faster than recorded).
// Draws come from the caller's seeded stream.
#pragma once

#include <optional>
#include <string>

#include "agent/conversation/think_time.hpp"
#include "agent/model_server/model_responder.hpp"
#include "common/rng.hpp"

namespace a3::agent::model_server {

class LatencyModel {
 public:
  // Throws std::invalid_argument naming the bad spec (or time scale) and the accepted forms.
  static LatencyModel parse(const std::string& spec, double time_scale = 1.0);

  // Seconds to wait before answering `reply` (its usage must carry prompt_tokens and
  // completion_tokens for the "tokens" form; missing counts are 0).
  double latency_s(const ResponderReply& reply, common::Rng& rng) const;

  // The mean per request where it does not depend on the reply (distributions), else nothing.
  std::optional<double> mean_s() const;
  // For the start-up line: "recorded", "model:GPT-4.1-mini (lognormal, mean 13.05 s)", ... and
  // the time scale when it is not 1.
  std::string describe() const;
  const std::string& spec() const { return spec_; }
  double time_scale() const { return time_scale_; }

 private:
  enum class Kind { kRecorded, kDistribution, kTokens };
  Kind kind_ = Kind::kRecorded;
  std::string spec_;
  double time_scale_ = 1.0;
  std::optional<ThinkTime> distribution_;
  double distribution_factor_ = 1.0;  // model-episode: turns per episode
  double prefill_tok_per_s_ = 0.0;
  double decode_tok_per_s_ = 0.0;
  double ttft_s_ = 0.0;
};

}  // namespace a3::agent::model_server
