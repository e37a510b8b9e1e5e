// `a3rig node linkemu` end to end: it prints and refits the slice profiles (the compiled-in
// file is what the fit gives), refuses bad settings naming the field, and relays messages
// published by another process over udpm, writing one record line per message (skipped
// with the fix-it message when multicast is not looped back; fails with A3_REQUIRE_UDPM=1).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <thread>

#include "a3lcm/link_message_t.hpp"
#include "common/lcm_bus.hpp"
#include "linkemu/slice_profile.hpp"
#include "tests/common/common_test_util.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/linkemu/linkemu_test_util.hpp"
#include "tests/test_support.hpp"

namespace a3::linkemu {
namespace {

using a3::test::a3rig;
using a3::test::quote;
using a3::test::run_command;

TEST(CliLinkemu, HelpNamesTheOptions) {
  const auto r = run_command(a3rig() + " node linkemu --help");
  EXPECT_EQ(r.exit_status, 0);
  for (const char* option : {"--trace", "--seed", "--slice", "--records", "--handover-ms", "--net-rate-hz",
                             "--reorder", "--ge-burst", "--fit-profiles", "--duration-s"}) {
    EXPECT_NE(r.output.find(option), std::string::npos) << option;
  }
}

TEST(CliLinkemu, PrintsAndRefitsTheProfiles) {
  const auto printed = run_command(a3rig() + " node linkemu --print-profiles");
  ASSERT_EQ(printed.exit_status, 0);
  const SliceProfiles a = parse_slice_profiles(nlohmann::json::parse(printed.output), "printed: ");
  EXPECT_EQ(to_json(a).dump(), to_json(default_slice_profiles()).dump());

  const auto fitted = run_command(a3rig() + " node linkemu --fit-profiles");
  ASSERT_EQ(fitted.exit_status, 0);
  const SliceProfiles b = parse_slice_profiles(nlohmann::json::parse(fitted.output), "fitted: ");
  // The file in the repository is exactly what the fit prints (6 significant digits).
  EXPECT_EQ(to_json(b).dump(), to_json(default_slice_profiles()).dump())
      << "linkemu/slice_profiles.json is stale: regenerate its fitted fields with "
         "`a3rig node linkemu --fit-profiles`";
}

TEST(CliLinkemu, BadSettingsAreRefusedNamingTheField) {
  a3::test::TempDir dir;
  const auto config = dir.path() / "link.json";
  std::ofstream(config) << R"({"handover_delay_ms": -1})";
  auto r = run_command(a3rig() + " node linkemu --lcm-url memq:// --config " + quote(config.string()), true);
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.output.find("link.json: /handover_delay_ms: -1 must be a number >= 0"), std::string::npos) << r.output;

  const auto trace = dir.path() / "trace.json";
  std::ofstream(trace) << R"([{"slice": "LTE", "lat_ms": 5, "jitter_ms": 1, "loss_pct": 0, "throughput_mbps": 9, "edge_load": 0.1}])";
  r = run_command(a3rig() + " node linkemu --lcm-url memq:// --trace " + quote(trace.string()), true);
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.output.find("trace.json: /0/slice: unknown slice 'LTE'"), std::string::npos) << r.output;
}

TEST(CliLinkemu, RunsForTheGivenDurationAndSummarises) {
  const auto r = run_command(a3rig() + " node linkemu --lcm-url memq:// --duration-s 0.3 --stats-every-s 0", true);
  EXPECT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("up: 0 in, 0 delivered"), std::string::npos) << r.output;
}

TEST(CliLinkemu, RelaysMessagesFromAnotherProcessAndWritesRecords) {
  const std::string url = a3::test::private_udpm_url();
  const char* require_env = std::getenv("A3_REQUIRE_UDPM");
  std::unique_ptr<common::LcmBus> bus;
  try {
    bus = std::make_unique<common::LcmBus>(url);
    bus->check_loopback(1000);
  } catch (const std::exception& e) {
    if (require_env != nullptr && std::string(require_env) == "1") FAIL() << e.what();
    GTEST_SKIP() << "LCM over " << url << " does not work on this host: " << e.what();
  }
  a3::test::TempDir dir;
  const auto records = dir.path() / "records.jsonl";
  std::mt19937_64 gen(std::random_device{}());
  const std::string suffix = "_CLI" + std::to_string(::getpid()) + "_" + std::to_string(gen() % 1000000);
  const LinkChannels channels = LinkChannels{}.with_suffix(suffix);
  a3::test::CommandResult result;
  std::thread node([&] {
    result = run_command(a3rig() + " node linkemu --lcm-url " + quote(url) + " --channel-suffix " + suffix +
                             " --slice URLLC --seed 3 --duration-s 3 --stats-every-s 0 --records " +
                             quote(records.string()),
                         true);
  });
  std::vector<a3lcm::link_message_t> got;
  bus->subscribe<a3lcm::link_message_t>(channels.up_rx, [&](const a3lcm::link_message_t& m, int64_t) { got.push_back(m); });
  // Wait until the node is up: its A3_NET shows it.
  bool node_up = false;
  bus->subscribe_raw(channels.net, [&](const std::string&, const uint8_t*, std::size_t, int64_t) { node_up = true; });
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (!node_up && std::chrono::steady_clock::now() < deadline) bus->handle_timeout(10);
  ASSERT_TRUE(node_up) << "no A3_NET from the node";
  for (int i = 0; i < 20; ++i) {
    auto m = test::make_message(i, "agent", 120);
    ASSERT_TRUE(bus->publish(channels.up_tx, m));
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (std::chrono::steady_clock::now() < until && got.size() < 20) bus->handle_timeout(10);
  node.join();
  EXPECT_EQ(result.exit_status, 0) << result.output;
  // URLLC loses 0.06 % of messages: all 20 arrive but for a rare loss.
  EXPECT_GE(got.size(), 19u);
  for (const auto& m : got) EXPECT_EQ(m.slice, "URLLC");
  std::ifstream in(records);
  int lines = 0;
  for (std::string line; std::getline(in, line); ++lines) {
    const auto record = nlohmann::json::parse(line);
    EXPECT_EQ(record["dir"], "up");
    EXPECT_EQ(record["net"]["slice"], "URLLC");
  }
  EXPECT_EQ(lines, 20);
  EXPECT_NE(result.output.find("20 records written"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace a3::linkemu
