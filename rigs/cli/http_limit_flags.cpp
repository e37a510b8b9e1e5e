// --max-connections, --header-timeout, --body-timeout; --allow-origin, --allow-host (see http_limit_flags.hpp).
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

namespace {

// A CLI11 check of one value by check_origin_policy: its message, or "" when well formed.
CLI::Validator origin_policy_check(bool is_origin) {
  return CLI::Validator(
      [is_origin](std::string& value) {
        agent::http::OriginPolicy one;
        (is_origin ? one.allowed_origins : one.allowed_hosts).push_back(value);
        try {
          agent::http::check_origin_policy(one);
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      is_origin ? "ORIGIN" : "NAME");
}

}  // namespace

std::vector<CLI::Option*> add_http_origin_flags(CLI::App& command, agent::http::OriginPolicy& origins) {
  return {command
              .add_option("--allow-origin", origins.allowed_origins,
                          "let a browser page on ORIGIN (scheme://host[:port], e.g. http://localhost:6274) call this "
                          "server, with CORS headers (repeatable). By default a request whose Origin is not the "
                          "server's own is refused 403")
              ->check(origin_policy_check(true)),
          command
              .add_option("--allow-host", origins.allowed_hosts,
                          "answer requests whose Host is NAME (repeatable; e.g. this machine's DNS name or a proxy's). "
                          "By default only the listening address (and localhost on loopback or 0.0.0.0) is answered, "
                          "others 403: a page that rebinds its DNS name to this address cannot reach the server")
              ->check(origin_policy_check(false))};
}

}  // namespace a3::rigs
