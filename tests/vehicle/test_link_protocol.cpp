// The link envelopes: actions and observations survive encode → LCM bytes → decode; an image's
// bytes are charged to the message; malformed messages are refused with the reason.
#include <gtest/gtest.h>

#include <vector>

#include "agent/link_protocol.hpp"
#include "common/runtime.hpp"

namespace a3::agent {
namespace {

// Through the LCM wire format, as the bus carries it (encoded, delivered, decoded).
a3lcm::link_message_t wire(const a3lcm::link_message_t& m) {
  common::VirtualRuntime rt;
  std::vector<a3lcm::link_message_t> received;
  rt.bus().subscribe<a3lcm::link_message_t>(
      "WIRE", [&received](const a3lcm::link_message_t& r, int64_t) { received.push_back(r); });
  EXPECT_TRUE(rt.bus().publish("WIRE", m));
  rt.run_until(1);
  EXPECT_EQ(received.size(), 1u);
  return received.empty() ? a3lcm::link_message_t{} : received.front();
}

a3lcm::link_message_t with_text(const std::string& text) {
  a3lcm::link_message_t m{};
  m.message_id = 9;
  m.kind = "mcp_call";
  m.payload.assign(text.begin(), text.end());
  m.payload_length = static_cast<int32_t>(m.payload.size());
  return m;
}

TEST(LinkProtocol, AnActionRoundTrips) {
  const nlohmann::json action = {{"type", "mcp"}, {"name", "set_waypoint"}, {"args", {{"x", 1.5}, {"y", -2}, {"z", 30}}}};
  const auto m = wire(agent::encode_action({4, 2, action}, 17, 1'234'000, "agent"));
  EXPECT_EQ(m.kind, "mcp_call");
  EXPECT_EQ(m.sender, "agent");
  EXPECT_EQ(m.message_id, 17);
  EXPECT_EQ(m.utime_us, 1'234'000);
  EXPECT_EQ(m.sent_utime_us, 1'234'000);
  EXPECT_EQ(m.payload_size_bytes, m.payload_length);
  std::string error;
  const auto a = decode_action(m, &error);
  ASSERT_TRUE(a.has_value()) << error;
  EXPECT_EQ(a->turn, 4);
  EXPECT_EQ(a->action_index, 2);
  EXPECT_EQ(a->action, action);
  const auto a2a = agent::encode_action({1, 0, {{"type", "a2a"}, {"task", "path_plan"}, {"to", "ground_station"}}}, 1, 0, "agent");
  EXPECT_EQ(a2a.kind, "a2a_message");
}

TEST(LinkProtocol, AnObservationRoundTripsAndAnImageChargesItsBytes) {
  const nlohmann::json obs = {{"tool", "capture_image"}, {"result", {{"status", "captured"}, {"image_id", "img-0001"}}}};
  const auto plain = wire(encode_observation({3, 1, obs}, 5, 99, "tool_server"));
  EXPECT_EQ(plain.kind, "observation");
  EXPECT_EQ(plain.payload_size_bytes, plain.payload_length);
  const auto image = wire(encode_observation({3, 1, obs}, 6, 99, "tool_server", 3'500'000));
  EXPECT_EQ(image.kind, "image");
  EXPECT_EQ(image.payload_size_bytes, 3'500'000 + image.payload_length);
  EXPECT_EQ(image.payload, plain.payload) << "the JSON carries only the reference";
  std::string error;
  const auto o = agent::decode_observation(image, &error);
  ASSERT_TRUE(o.has_value()) << error;
  EXPECT_EQ(o->turn, 3);
  EXPECT_EQ(o->action_index, 1);
  EXPECT_EQ(o->obs, obs);
  const auto huge = encode_observation({1, 0, obs}, 7, 0, "tool_server", int64_t{1} << 40);
  EXPECT_EQ(huge.payload_size_bytes, std::numeric_limits<int32_t>::max()) << "saturates, never wraps";
}

TEST(LinkProtocol, MalformedMessagesAreRefusedWithTheReason) {
  struct Case {
    std::string text, reason;
  };
  const Case cases[] = {
      {"", "is not a JSON object"},
      {"{\"turn\": 1,", "is not a JSON object"},
      {"[1, 2]", "is not a JSON object"},
      {R"({"action_index": 0, "action": {}})", "lacks integer turn/action_index"},
      {R"({"turn": "1", "action_index": 0, "action": {}})", "lacks integer turn/action_index"},
      {R"({"turn": 1, "action_index": 0.5, "action": {}})", "lacks integer turn/action_index"},
      {R"({"turn": 1, "action_index": 0})", "has no action object"},
      {R"({"turn": 1, "action_index": 0, "action": [1]})", "has no action object"},
  };
  for (const auto& c : cases) {
    std::string error;
    EXPECT_FALSE(decode_action(with_text(c.text), &error).has_value()) << c.text;
    EXPECT_NE(error.find(c.reason), std::string::npos) << c.text << ": " << error;
    EXPECT_NE(error.find("link message 9"), std::string::npos) << error;
  }
  std::string error;
  EXPECT_FALSE(agent::decode_observation(with_text(R"({"turn": 1, "action_index": 0, "action": {}})"), &error));
  EXPECT_NE(error.find("has no obs object"), std::string::npos);
  const std::string big(kMaxLinkJsonBytes + 1, ' ');
  EXPECT_FALSE(decode_action(with_text(big), &error));
  EXPECT_NE(error.find("over the limit"), std::string::npos);
}

}  // namespace
}  // namespace a3::agent
