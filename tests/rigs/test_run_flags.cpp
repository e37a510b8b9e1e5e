// Run options are parsed once into typed fields and written back by the same table
// (rigs/run/run_flags.hpp, rigs/cli/run_flag_options.hpp): what to_argv writes parses back to the
// same options, unset options and switches that are off are left out, and a bad name is refused
// with the names the owning component lists.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "rigs/cli/run_flag_options.hpp"
#include "rigs/run/run_flags.hpp"

namespace a3::rigs {
namespace {

constexpr std::initializer_list<RunFlag> kEveryFlag = {
    RunFlag::kScenario, RunFlag::kAgent,   RunFlag::kThinkTime,  RunFlag::kRuntime,      RunFlag::kSlice,
    RunFlag::kSeed,     RunFlag::kOut,     RunFlag::kRtf,        RunFlag::kSync,         RunFlag::kLcmUrl,
    RunFlag::kCan,      RunFlag::kIntegrator, RunFlag::kDynamicsRate, RunFlag::kSharedDir, RunFlag::kMaxTurns,
    RunFlag::kMinTurns, RunFlag::kNoLcmLog, RunFlag::kNoPlot,     RunFlag::kNoReport,     RunFlag::kQuiet};

RunOptions parsed(std::vector<std::string> argv) {
  CLI::App app;
  RunOptions o;
  add_run_flags(app, o, kEveryFlag);
  std::vector<const char*> args = {"a3rig"};
  for (const std::string& a : argv) args.push_back(a.c_str());
  app.parse(static_cast<int>(args.size()), args.data());
  return o;
}

TEST(RunFlags, WhatToArgvWritesParsesBackToTheSameOptions) {
  RunOptions o;
  o.scenario = "gen:7:hard";
  o.agent = "replay:x.json";
  o.think_time = "model:gpt-4o";
  o.runtime = Runtime::kVirtual;
  o.slice = linkemu::Slice::kMmtc;
  o.seed = 1337;
  o.out_dir = "out/x y";
  o.real_time_factor = 0.1;
  o.sync = Sync::kFree;
  o.lcm_url = "udpm://239.255.76.67:7700?ttl=0";
  o.can = "vcan0";
  o.integrator = dynamics::IntegratorKind::kCvode;
  o.dynamics_rate_hz = 333.3;
  o.shared_dir = "/data/shared";
  o.max_turns = 20;
  o.min_turns = 3;
  o.write_lcm_log = o.write_plot = o.write_report = false;
  o.quiet = true;
  const std::vector<std::string> argv = to_argv(o, kEveryFlag);
  EXPECT_NE(std::find(argv.begin(), argv.end(), "0.1"), argv.end()) << "the shortest exact text, not 0.1000...01";
  const RunOptions back = parsed(argv);
  EXPECT_EQ(back.scenario, o.scenario);
  EXPECT_EQ(back.agent, o.agent);
  EXPECT_EQ(back.think_time, o.think_time);
  EXPECT_EQ(back.runtime, o.runtime);
  EXPECT_EQ(back.slice, o.slice);
  EXPECT_EQ(back.seed, o.seed);
  EXPECT_EQ(back.out_dir, o.out_dir);
  EXPECT_EQ(back.real_time_factor, o.real_time_factor);
  EXPECT_EQ(back.sync, o.sync);
  EXPECT_EQ(back.lcm_url, o.lcm_url);
  EXPECT_EQ(back.can, o.can);
  EXPECT_EQ(back.integrator, o.integrator);
  EXPECT_EQ(back.dynamics_rate_hz, o.dynamics_rate_hz);
  EXPECT_EQ(back.shared_dir, o.shared_dir);
  EXPECT_EQ(back.max_turns, o.max_turns);
  EXPECT_EQ(back.min_turns, o.min_turns);
  EXPECT_FALSE(back.write_lcm_log || back.write_plot || back.write_report);
  EXPECT_TRUE(back.quiet);
}

TEST(RunFlags, UnsetOptionsAndSwitchesThatAreOffAreLeftOut) {
  const RunOptions o;  // no slice override, every output on, not quiet, no LCM URL
  const std::vector<std::string> argv =
      to_argv(o, {RunFlag::kSlice, RunFlag::kLcmUrl, RunFlag::kNoLcmLog, RunFlag::kNoPlot, RunFlag::kQuiet, RunFlag::kSeed});
  EXPECT_EQ(argv, (std::vector<std::string>{"--seed", "42"}));
  EXPECT_FALSE(parsed({}).slice.has_value());
}

TEST(RunFlags, NamesComeFromTheComponentsThatOwnThem) {
  EXPECT_EQ(parsed({"--slice", "URLLC"}).slice, linkemu::Slice::kUrllc);
  EXPECT_EQ(parsed({"--integrator", "ode"}).integrator, dynamics::IntegratorKind::kOde);
  try {
    parsed({"--integrator", "euler"});
    FAIL() << "euler was taken";
  } catch (const CLI::ParseError& e) {
    const std::string what = e.what();
    for (const std::string& name : dynamics::integrator_names()) EXPECT_NE(what.find(name), std::string::npos) << what;
  }
  EXPECT_THROW(parsed({"--slice", "5G"}), CLI::ParseError);
  EXPECT_THROW(parsed({"--runtime", "sometimes"}), CLI::ParseError);
}

}  // namespace
}  // namespace a3::rigs
