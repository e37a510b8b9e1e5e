// Which requests an HTTP server of the rig (serve-model, mcp --http) accepts by where they say
// they come from: the protection against DNS rebinding and against pages in a browser that the
// MCP specification asks of a local server.
//
// - Host: the name the client used must be one this server answers to: the address it listens
//   on, "localhost" and any loopback address when that is a loopback address, any IP literal and
//   "localhost" when it listens on every interface (0.0.0.0, ::), and the names given with
//   --allow-host. A port, when given, must be the server's. A page that rebinds its own DNS name
//   to 127.0.0.1 sends its own name: 403.
// - Origin (sent by browsers): absent (programs: curl, SDKs) or the server's own origin is
//   served; any other origin only when given with --allow-origin, and then with the CORS
//   headers a browser needs (preflight answered 204). Otherwise 403, "null" included.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "agent/http/http_limits.hpp"

namespace a3::agent::http {

struct OriginPolicy {
  std::vector<std::string> allowed_origins;  // --allow-origin: "scheme://host[:port]" pages allowed to call
  std::vector<std::string> allowed_hosts;    // --allow-host: more names clients may reach the server by
  std::string cors_allow_headers = "Content-Type, Accept, Authorization";  // an allowed page may send
  std::string cors_expose_headers;                                         // an allowed page may read
};

// Throws std::invalid_argument naming the flag and value of an origin that is not
// scheme://host[:port] (no path) or "null", or a host name with a port, path or space.
void check_origin_policy(const OriginPolicy& policy);

// The policy applied to a server bound to `listen_host`:`port`.
class OriginCheck {
 public:
  OriginCheck(OriginPolicy policy, std::string listen_host, int port);

  // 403 with the reason for a Host this server does not answer to or a foreign Origin.
  std::optional<HttpRefusal> refusal(const std::optional<std::string>& host, const std::optional<std::string>& origin) const;
  // True for an Origin given with --allow-origin that is not the server's own: its responses
  // carry Access-Control-Allow-Origin.
  bool is_allowed_cross_origin(const std::string& origin) const;
  const OriginPolicy& policy() const { return policy_; }

 private:
  bool answers_to(const std::string& name) const;
  bool is_own_origin(const std::string& origin) const;

  OriginPolicy policy_;
  std::string listen_host_;
  int port_;
};

}  // namespace a3::agent::http
