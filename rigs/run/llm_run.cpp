// The llm agent's endpoint for a run, its agent, and the check before take-off.
#include "rigs/run/llm_run.hpp"

#include <algorithm>
#include <stdexcept>

#include "agent/llm/llm_agent.hpp"

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
  e.stream = o.llm_stream;
  if (o.llm_retries < 0) throw std::invalid_argument("--llm-retries must be >= 0, got " + std::to_string(o.llm_retries));
  e.max_retries = o.llm_retries;
  e.json_output = agent::llm::parse_tool_mode(o.llm_tools) == agent::llm::ToolMode::kJson;
  if (e.provider.empty()) e.provider = agent::llm::provider_from_base_url(e.base_url);
  return e;
}

std::unique_ptr<agent::Agent> make_llm_agent(const RunOptions& o) {
  agent::llm::LlmAgentOptions options;
  options.mode = agent::llm::parse_tool_mode(o.llm_tools);
  return std::make_unique<agent::llm::LlmAgent>(std::make_unique<agent::llm::LlmClient>(llm_endpoint(o)),
                                                agent::ToolCatalog::builtin(), options);
}

// A 16-token answer takes seconds; an endpoint that takes the connection and stays silent must
// not hold the run for the whole --llm-timeout (180 s by default), twice.
constexpr double kProbeTimeout_s = 10.0;

void check_llm_endpoint(const agent::llm::LlmEndpoint& endpoint) {
  agent::llm::LlmEndpoint probe = endpoint;
  probe.total_timeout_s = std::min(endpoint.total_timeout_s, kProbeTimeout_s);
  probe.connect_timeout_s = std::min(endpoint.connect_timeout_s, kProbeTimeout_s);
  probe.json_output = false;
  probe.stream = false;
  probe.max_tokens = 16;
  probe.max_retries = std::min(endpoint.max_retries, 1);
  probe.backoff_initial_s = 1.0;
  agent::llm::LlmClient client(probe);
  const agent::llm::LlmCallResult r = client.chat({{"user", "Reply with the word ok."}});
  if (agent::llm::is_endpoint_failure(r)) {
    throw EndpointUnreachable("the LLM endpoint " + endpoint.base_url + " (model " + endpoint.model +
                              ") does not answer: " + r.error);
  }
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
