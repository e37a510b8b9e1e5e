// The flags that bound what one client may take of an HTTP server of the rig (serve-model,
// mcp --http): --max-connections, --header-timeout, --body-timeout (agent/http/http_limits.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "agent/http/http_limits.hpp"

namespace a3::rigs {

// Returns the options added (a command may refuse them when it serves no HTTP).
// `connection_flag`: the names of the connection limit's flag (serve-model adds its older --threads).
std::vector<CLI::Option*> add_http_limit_flags(CLI::App& command, agent::http::HttpLimits& limits,
                                               const std::string& connection_flag = "--max-connections");

}  // namespace a3::rigs
