// The Host and Origin rules every HTTP server of the rig applies (agent/http/origin_policy.hpp),
// for each kind of listening address.
#include <gtest/gtest.h>

#include "agent/http/origin_policy.hpp"

namespace a3::agent::http {
namespace {

std::optional<int> status(const OriginCheck& check, std::optional<std::string> host, std::optional<std::string> origin = {}) {
  const auto refused = check.refusal(host, origin);
  return refused ? std::optional<int>(refused->status) : std::nullopt;
}

TEST(OriginCheck, OnLoopbackAnswersLoopbackNamesOnItsPortOnly) {
  const OriginCheck check({}, "127.0.0.1", 8088);
  EXPECT_EQ(status(check, "127.0.0.1:8088"), std::nullopt);
  EXPECT_EQ(status(check, "localhost:8088"), std::nullopt);
  EXPECT_EQ(status(check, "LOCALHOST:8088"), std::nullopt);
  EXPECT_EQ(status(check, "127.0.0.1"), std::nullopt);  // no port: as a client without one sends it
  EXPECT_EQ(status(check, "[::1]:8088"), std::nullopt);
  EXPECT_EQ(status(check, std::nullopt), std::nullopt);  // HTTP/1.0, no Host
  EXPECT_EQ(status(check, "evil.example:8088"), 403);
  EXPECT_EQ(status(check, "127.0.0.1.evil.example:8088"), 403);
  EXPECT_EQ(status(check, "localhost:8089"), 403);
  EXPECT_EQ(status(check, "10.0.0.1:8088"), 403);
  EXPECT_EQ(status(check, ""), 403);
  EXPECT_EQ(status(check, "a:b:c"), 403);
}

TEST(OriginCheck, OnEveryInterfaceAnswersAnyAddressButNoForeignName) {
  const OriginCheck check({}, "0.0.0.0", 80);
  EXPECT_EQ(status(check, "192.0.2.7"), std::nullopt);
  EXPECT_EQ(status(check, "[2001:db8::1]"), std::nullopt);
  EXPECT_EQ(status(check, "localhost"), std::nullopt);
  EXPECT_EQ(status(check, "rebind.evil.example"), 403);
}

TEST(OriginCheck, OnOneAddressAnswersThatAddressAndAllowedNames) {
  OriginPolicy policy;
  policy.allowed_hosts = {"Rig.Lab.Example"};
  const OriginCheck check(policy, "192.0.2.7", 9000);
  EXPECT_EQ(status(check, "192.0.2.7:9000"), std::nullopt);
  EXPECT_EQ(status(check, "rig.lab.example:9000"), std::nullopt);
  EXPECT_EQ(status(check, "localhost:9000"), 403);
  EXPECT_EQ(status(check, "192.0.2.8:9000"), 403);
}

TEST(OriginCheck, OnlyTheServersOwnOriginOrAnAllowedOneIsServed) {
  OriginPolicy policy;
  policy.allowed_origins = {"http://localhost:6274/"};
  const OriginCheck check(policy, "127.0.0.1", 8765);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "http://127.0.0.1:8765"), std::nullopt);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "http://localhost:8765"), std::nullopt);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "HTTP://LOCALHOST:6274"), std::nullopt);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "http://localhost:6275"), 403);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "https://localhost:8765"), 403);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "http://evil.example:8765"), 403);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "null"), 403);
  EXPECT_EQ(status(check, "127.0.0.1:8765", "http://localhost"), 403);  // port 80 is another origin
  EXPECT_TRUE(check.is_allowed_cross_origin("http://localhost:6274"));
  EXPECT_FALSE(check.is_allowed_cross_origin("http://127.0.0.1:8765"));  // its own: no CORS needed
}

TEST(OriginCheck, MalformedFlagsAreRefusedNamingTheFlag) {
  for (const std::string bad : {"localhost:6274", "http://x/path", "http://", "*", "http://a b"}) {
    OriginPolicy policy;
    policy.allowed_origins = {bad};
    try {
      check_origin_policy(policy);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--allow-origin"), std::string::npos) << e.what();
    }
  }
  OriginPolicy host;
  host.allowed_hosts = {"rig.example:80"};
  EXPECT_THROW(check_origin_policy(host), std::invalid_argument);
}

}  // namespace
}  // namespace a3::agent::http
