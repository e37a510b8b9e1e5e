// What `a3rig run --agent llm` talks to: the OpenAI-compatible endpoint from the run's options
// (base URL, model, token cap, timeouts) and the environment (A3_LLM_BASE_URL, A3_LLM_MODEL,
// A3_LLM_PROVIDER, and the API key, which only the environment gives: A3_LLM_API_KEY,
// A3_LLM_API_KEY_FILE or OPENAI_API_KEY), and how the episode names that agent.
#pragma once

#include <string>

#include "agent/llm/llm_client.hpp"
#include "rigs/core/run_options.hpp"

namespace a3::rigs {

// Throws std::invalid_argument naming what is missing (never the key).
agent::llm::LlmEndpoint llm_endpoint(const RunOptions& options);

// The episode's _meta "model" and "provider" for an llm agent (e.g. "anthropic/claude-haiku-4.5",
// "openrouter"); empty strings when options.agent is not "llm" or the endpoint is not resolvable.
struct LlmAgentIdentity {
  std::string model;
  std::string provider;
};
LlmAgentIdentity llm_agent_identity(const RunOptions& options);

}  // namespace a3::rigs
