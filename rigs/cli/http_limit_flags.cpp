// --max-connections, --header-timeout, --body-timeout (see http_limit_flags.hpp).
#include "rigs/cli/http_limit_flags.hpp"

namespace a3::rigs {

std::vector<CLI::Option*> add_http_limit_flags(CLI::App& command, agent::http::HttpLimits& limits,
                                               const std::string& connection_flag) {
  std::vector<CLI::Option*> added;
  added.push_back(command
      .add_option(connection_flag, limits.max_connections,
                  "connections served at once, a thread each (default 256); beyond, a connection is answered 503 "
                  "with Retry-After: 1")
      ->check(CLI::Range(1, 4096)));
  added.push_back(command
      .add_option("--header-timeout", limits.header_timeout_s,
                  "seconds a request's line and headers may take to arrive, from its first byte (default 10); "
                  "later: 408 and the connection is closed")
      ->check(CLI::Range(0.001, 3600.0)));
  added.push_back(command
      .add_option("--body-timeout", limits.body_timeout_s,
                  "seconds a request's body may take to arrive once its head has (default 60); later: 408 and the "
                  "connection is closed")
      ->check(CLI::Range(0.001, 3600.0)));
  return added;
}

}  // namespace a3::rigs
