// The flags that bound what one client may take of an HTTP server of the rig (serve-model,
// mcp --http): --max-connections, --header-timeout, --body-timeout (agent/http/http_limits.hpp);
// and the flags that widen whom it answers: --allow-origin, --allow-host (agent/http/origin_policy.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "agent/http/http_limits.hpp"
#include "agent/http/origin_policy.hpp"

namespace a3::rigs {

// Returns the options added (a command may refuse them when it serves no HTTP).
// `connection_flag`: the names of the connection limit's flag (serve-model adds its older --threads).
std::vector<CLI::Option*> add_http_limit_flags(CLI::App& command, agent::http::HttpLimits& limits,
                                               const std::string& connection_flag = "--max-connections");

// --allow-origin ORIGIN and --allow-host NAME (both repeatable); returns the options added.
std::vector<CLI::Option*> add_http_origin_flags(CLI::App& command, agent::http::OriginPolicy& origins);

}  // namespace a3::rigs
