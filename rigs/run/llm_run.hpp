// What `a3rig run --agent llm` talks to: the OpenAI-compatible endpoint from the run's options
// (base URL, model, token cap, timeouts, streaming) and the environment (A3_LLM_BASE_URL,
// A3_LLM_MODEL, A3_LLM_PROVIDER, and the API key, which only the environment gives:
// A3_LLM_API_KEY, A3_LLM_API_KEY_FILE or OPENAI_API_KEY), the llm agent made from them
// (--llm-tools native|json), the check of the endpoint before take-off, and how the episode
// names that agent.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "agent/conversation/agent.hpp"
#include "agent/llm/llm_client.hpp"
#include "rigs/run/run_options.hpp"

namespace a3::rigs {

// Throws std::invalid_argument naming what is missing (never the key).
agent::llm::LlmEndpoint llm_endpoint(const RunOptions& options);

// The llm agent of a run: its endpoint, and --llm-tools (native: tool calls, json output off;
// json: the paper's JSON object). Throws std::invalid_argument as llm_endpoint, or for a bad
// --llm-tools.
std::unique_ptr<agent::Agent> make_llm_agent(const RunOptions& options);

// The endpoint did not answer before take-off.
class EndpointUnreachable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Before take-off: one short chat call to the endpoint (16 completion tokens at most, one retry
// after 1 s). Throws EndpointUnreachable, naming the endpoint and what failed, when the failure
// is the endpoint's as `a3rig generate` judges it (agent::llm::is_endpoint_failure: no answer,
// 401, 403, 404, 408, 429, 5xx); any other answer (a 400 to the short question included) means
// the endpoint is there.
void check_llm_endpoint(const agent::llm::LlmEndpoint& endpoint);

// The episode's _meta "model" and "provider" for an llm agent (e.g. "anthropic/claude-haiku-4.5",
// "openrouter"); empty strings when options.agent is not "llm" or the endpoint is not resolvable.
struct LlmAgentIdentity {
  std::string model;
  std::string provider;
};
LlmAgentIdentity llm_agent_identity(const RunOptions& options);

}  // namespace a3::rigs
