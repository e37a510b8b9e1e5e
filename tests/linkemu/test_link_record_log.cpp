// The per-message log: one JSON object per line with every field of the record, strings
// escaped, numbers exact enough to rebuild the timing.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "linkemu/link_record_log.hpp"
#include "tests/common/common_test_util.hpp"

namespace a3::linkemu {
namespace {

a3lcm::link_record_t make_record(int64_t id, int8_t outcome) {
  a3lcm::link_record_t r{};
  r.utime_us = 1'000'000 + id;
  r.direction = id % 2 ? "down" : "up";
  r.message_id = id;
  r.sender = "agent \"α\"\n";
  r.kind = "mcp_call";
  r.sent_utime_us = 999'000 + id;
  r.size_bytes = 5'000'000;
  r.outcome = outcome;
  r.drop_reason = outcome == a3lcm::link_record_t::DROPPED ? "bad_size: payload_size_bytes -5 is negative" : "";
  r.delivery_utime_us = outcome == a3lcm::link_record_t::DELIVERED ? 18'391'305 + id : -1;
  r.queue_ms = 12.5;
  r.serialization_ms = 17391.305;
  r.latency_ms = 50.125;
  r.slice = "mMTC";
  r.net_lat_ms = 50.0;
  r.net_jitter_ms = 7.25;
  r.net_loss_pct = 2.387;
  r.net_throughput_mbps = 2.3;
  r.net_edge_load = 0.757;
  r.net_degraded = true;
  return r;
}

TEST(LinkRecordLog, OneJsonObjectPerRecord) {
  a3::test::TempDir dir;
  const auto path = dir.path() / "records.jsonl";
  std::vector<a3lcm::link_record_t> records = {
      make_record(1, a3lcm::link_record_t::DELIVERED), make_record(2, a3lcm::link_record_t::LOST),
      make_record(3, a3lcm::link_record_t::DROPPED)};
  {
    LinkRecordLog log(path);
    for (const auto& r : records) log.write(r);
    EXPECT_EQ(log.lines(), 3u);
    log.close();
  }
  std::ifstream in(path);
  std::vector<nlohmann::json> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(lines.size(), 3u);
  const nlohmann::json& a = lines[0];
  EXPECT_EQ(a["t_us"], 1'000'001);
  EXPECT_EQ(a["dir"], "down");
  EXPECT_EQ(a["id"], 1);
  EXPECT_EQ(a["sender"], "agent \"α\"\n");
  EXPECT_EQ(a["kind"], "mcp_call");
  EXPECT_EQ(a["sent_us"], 999'001);
  EXPECT_EQ(a["size_bytes"], 5'000'000);
  EXPECT_EQ(a["outcome"], "delivered");
  EXPECT_EQ(a["delivery_us"], 18'391'306);
  EXPECT_DOUBLE_EQ(a["serialization_ms"].get<double>(), 17391.305);
  EXPECT_DOUBLE_EQ(a["latency_ms"].get<double>(), 50.125);
  EXPECT_EQ(a["net"]["slice"], "mMTC");
  EXPECT_DOUBLE_EQ(a["net"]["loss_pct"].get<double>(), 2.387);
  EXPECT_DOUBLE_EQ(a["net"]["edge_load"].get<double>(), 0.757);
  EXPECT_EQ(a["net"]["degraded"], true);
  EXPECT_EQ(lines[1]["outcome"], "lost");
  EXPECT_EQ(lines[1]["delivery_us"], -1);
  EXPECT_EQ(lines[2]["outcome"], "dropped");
  EXPECT_EQ(lines[2]["drop_reason"], "bad_size: payload_size_bytes -5 is negative");
}

TEST(LinkRecordLog, UnwritablePathIsNamed) {
  try {
    LinkRecordLog log("/nonexistent-folder/records.jsonl");
    FAIL() << "opened a file in a folder that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/records.jsonl"), std::string::npos);
  }
}

}  // namespace
}  // namespace a3::linkemu
