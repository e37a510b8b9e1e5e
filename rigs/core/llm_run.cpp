// The llm agent's endpoint for a run.
#include "rigs/core/llm_run.hpp"

#include <stdexcept>

namespace a3::rigs {

agent::llm::LlmEndpoint llm_endpoint(const RunOptions& o) {
  agent::llm::LlmEndpoint e = agent::llm::endpoint_from_environment(o.llm_base_url, o.llm_model);
  if (o.llm_max_tokens < 1) {
    throw std::invalid_argument("--llm-max-tokens must be >= 1, got " + std::to_string(o.llm_max_tokens));
  }
  if (!(o.llm_connect_timeout_s > 0.0) || !(o.llm_timeout_s > 0.0)) {
    throw std::invalid_argument("--llm-timeout and the connect timeout must be > 0 s");
  }
  e.max_tokens = o.llm_max_tokens;
  e.connect_timeout_s = o.llm_connect_timeout_s;
  e.total_timeout_s = o.llm_timeout_s;
  if (e.provider.empty()) e.provider = agent::llm::provider_from_base_url(e.base_url);
  return e;
}

LlmAgentIdentity llm_agent_identity(const RunOptions& o) {
  if (o.agent != "llm") return {};
  try {
    const agent::llm::LlmEndpoint e = llm_endpoint(o);
    return {e.model, e.provider};
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace a3::rigs
