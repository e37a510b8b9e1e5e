// Host and Origin checks (origin_policy.hpp).
#include "agent/http/origin_policy.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <regex>
#include <stdexcept>

#include "agent/http/request_checks.hpp"

namespace a3::agent::http {
namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

// "name", "name:port", "[v6]" or "[v6]:port" into the name (brackets removed) and the port text.
struct HostPort {
  std::string name;
  std::string port;
};
std::optional<HostPort> split_host_port(std::string_view text) {
  if (text.empty()) return std::nullopt;
  if (text.front() == '[') {
    const std::size_t close = text.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    const std::string_view rest = text.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') return std::nullopt;
    return HostPort{lower(text.substr(1, close - 1)), std::string(rest.empty() ? rest : rest.substr(1))};
  }
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos) return HostPort{lower(text), ""};
  if (text.find(':', colon + 1) != std::string_view::npos) return std::nullopt;
  return HostPort{lower(text.substr(0, colon)), std::string(text.substr(colon + 1))};
}

enum class Address { kName, kLoopback, kAny, kOther };

Address kind_of(const std::string& name) {
  in_addr v4{};
  in6_addr v6{};
  if (::inet_pton(AF_INET, name.c_str(), &v4) == 1) {
    const uint32_t host_order = ntohl(v4.s_addr);
    if (host_order == 0) return Address::kAny;
    return (host_order >> 24) == 127 ? Address::kLoopback : Address::kOther;
  }
  if (::inet_pton(AF_INET6, name.c_str(), &v6) == 1) {
    if (IN6_IS_ADDR_UNSPECIFIED(&v6)) return Address::kAny;
    return IN6_IS_ADDR_LOOPBACK(&v6) ? Address::kLoopback : Address::kOther;
  }
  return name == "localhost" ? Address::kLoopback : Address::kName;
}

bool is_ip_literal(const std::string& name) {
  in_addr v4{};
  in6_addr v6{};
  return ::inet_pton(AF_INET, name.c_str(), &v4) == 1 || ::inet_pton(AF_INET6, name.c_str(), &v6) == 1;
}

// An origin as compared: lower case, no trailing slash.
std::string normal_origin(std::string_view origin) {
  std::string out = lower(origin);
  while (!out.empty() && out.back() == '/') out.pop_back();
  return out;
}

const std::regex& origin_syntax() {
  static const std::regex kOrigin(R"(^[a-z][a-z0-9+.-]*://(\[[0-9a-f:.]+\]|[a-z0-9._~%-]+)(:[0-9]{1,5})?$)");
  return kOrigin;
}

}  // namespace

void check_origin_policy(const OriginPolicy& policy) {
  for (const std::string& origin : policy.allowed_origins) {
    const std::string normal = normal_origin(origin);
    if (normal != "null" && !std::regex_match(normal, origin_syntax())) {
      throw std::invalid_argument("--allow-origin '" + origin + "': expected scheme://host[:port] (e.g. http://localhost:6274), no path");
    }
  }
  static const std::regex kName(R"(^[A-Za-z0-9._-]+$|^\[?[0-9A-Fa-f:.]+\]?$)");
  for (const std::string& host : policy.allowed_hosts) {
    if (!std::regex_match(host, kName)) {
      throw std::invalid_argument("--allow-host '" + host + "': expected a host name or address, without port or path");
    }
  }
}

OriginCheck::OriginCheck(OriginPolicy policy, std::string listen_host, int port)
    : policy_(std::move(policy)), listen_host_(lower(listen_host)), port_(port) {
  check_origin_policy(policy_);
  for (std::string& origin : policy_.allowed_origins) origin = normal_origin(origin);
  for (std::string& host : policy_.allowed_hosts) {
    host = lower(host);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  }
}

bool OriginCheck::answers_to(const std::string& name) const {
  if (std::find(policy_.allowed_hosts.begin(), policy_.allowed_hosts.end(), name) != policy_.allowed_hosts.end()) return true;
  const Address listening = kind_of(listen_host_);
  switch (listening) {
    case Address::kAny: return is_ip_literal(name) || name == "localhost";
    case Address::kLoopback: return kind_of(name) == Address::kLoopback;
    default: return name == listen_host_;
  }
}

bool OriginCheck::is_own_origin(const std::string& origin) const {
  const std::string prefix = "http://";
  if (origin.rfind(prefix, 0) != 0) return false;
  const auto host = split_host_port(std::string_view(origin).substr(prefix.size()));
  if (!host) return false;
  const std::string port = host->port.empty() ? "80" : host->port;
  return port == std::to_string(port_) && answers_to(host->name);
}

bool OriginCheck::is_allowed_cross_origin(const std::string& origin) const {
  const std::string normal = normal_origin(origin);
  if (is_own_origin(normal)) return false;
  return std::find(policy_.allowed_origins.begin(), policy_.allowed_origins.end(), normal) != policy_.allowed_origins.end();
}

std::optional<HttpRefusal> OriginCheck::refusal(const std::optional<std::string>& host,
                                                const std::optional<std::string>& origin) const {
  if (host) {
    const auto parts = split_host_port(*host);
    const bool port_ok = parts && (parts->port.empty() || parts->port == std::to_string(port_));
    if (!parts || !port_ok || !answers_to(parts->name)) {
      return HttpRefusal{403, "forbidden: Host '" + shown_header_value(*host, 80) + "' is not an address of this server (DNS rebinding "
                              "protection; start the server with --allow-host NAME to answer to another name)"};
    }
  }
  if (origin && !is_own_origin(normal_origin(*origin)) && !is_allowed_cross_origin(*origin)) {
    return HttpRefusal{403, "forbidden: cross-origin request from Origin '" + shown_header_value(*origin, 80) +
                            "' (start the server with --allow-origin ORIGIN to allow a page there)"};
  }
  return std::nullopt;
}

}  // namespace a3::agent::http
