// `a3rig validate` and `a3rig score` on hostile files: nesting that overflowed the stack of a
// recursive parser (131 KB of '[', 200k `{"a":`), an episode with a duplicate key, and a file
// whose name is not UTF-8. Each is an invalid episode (exit 1, no signal) or a clean JSON output.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sstream>

#include "tests/eval/episode_builder.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/test_support.hpp"

namespace a3 {
namespace {

using test::a3rig;
using test::quote;
using test::run_command;

std::string nested_objects(int depth) {
  std::string text;
  for (int i = 0; i < depth; ++i) text += "{\"a\":";
  return text + "1" + std::string(depth, '}');
}

// One folder of a model with a good episode and the given bad ones.
struct Corpus {
  test::TempDir dir{"cli-json-faults"};
  std::filesystem::path model = dir.path() / "acme" / "agent" / "uav";
  Corpus() { test::write_json(model / "sc-0000-ep-00.json", test::make_episode()); }
};

TEST(CliJsonFaults, DeepNestingIsInvalidNotACrash) {
  Corpus c;
  test::write_text(c.model / "sc-0001-ep-00.json", std::string(131072, '['));
  test::write_text(c.model / "sc-0002-ep-00.json", nested_objects(200000));
  auto r = run_command(a3rig() + " validate " + quote(c.model.string()), true);
  EXPECT_EQ(r.exit_status, 1) << r.output;  // -1 when a signal ended it
  EXPECT_NE(r.output.find("INVALID " + (c.model / "sc-0001-ep-00.json").string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sc-0002-ep-00.json: /a/a/a/a"), std::string::npos) << r.output.substr(0, 2000);
  EXPECT_NE(r.output.find("json-depth: arrays/objects nested deeper than the limit of 256"), std::string::npos);
  EXPECT_NE(r.output.find("3 files: 1 valid episodes, 0 failure stubs, 2 invalid"), std::string::npos) << r.output;

  r = run_command(a3rig() + " score --format csv " + quote(c.dir.path().string()), true);
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("acme/agent,uav,"), std::string::npos) << r.output;
}

TEST(CliJsonFaults, ADuplicateKeyMakesTheEpisodeInvalid) {
  Corpus c;
  std::string text = test::make_episode().dump();
  text.replace(text.find("\"success\":true"), 14, "\"success\":false,\"success\":true");
  test::write_text(c.model / "sc-0001-ep-00.json", text);
  auto r = run_command(a3rig() + " validate --format json " + quote((c.model / "sc-0001-ep-00.json").string()));
  EXPECT_EQ(r.exit_status, 1) << r.output;
  const auto row = nlohmann::json::parse(r.output);
  EXPECT_EQ(row["status"], "invalid");
  EXPECT_EQ(row["violations"][0]["rule"], "json-duplicate-key");
  EXPECT_EQ(row["violations"][0]["path"], "");
  EXPECT_NE(row["violations"][0]["message"].get<std::string>().find("\"success\""), std::string::npos);

  r = run_command(a3rig() + " score --format csv " + quote(c.dir.path().string()), true);
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("sc-0001-ep-00.json: (root): json-duplicate-key: duplicate key \"success\""),
            std::string::npos)
      << r.output;
}

TEST(CliJsonFaults, AFileNameThatIsNotUtf8GivesValidJsonOutputs) {
  Corpus c;
  const std::string bad_name = "sc-0001-ep-00\xff.json";  // not an episode name: taken as given
  test::write_json(c.model / bad_name, test::make_episode());
  auto r = run_command(a3rig() + " validate --format json " + quote((c.model / bad_name).string()));
  EXPECT_EQ(r.exit_status, 0) << r.output;
  nlohmann::json row;
  ASSERT_NO_THROW(row = nlohmann::json::parse(r.output)) << r.output;
  EXPECT_EQ(row["status"], "valid");
  EXPECT_NE(row["file"].get<std::string>().find("sc-0001-ep-00\xef\xbf\xbd.json"), std::string::npos);

  const auto jsonl = c.dir.path() / "per-episode.jsonl";
  r = run_command(a3rig() + " score -q --format json --per-episode " + quote(jsonl.string()) + " " +
                      quote(c.dir.path().string()) + " " + quote((c.model / bad_name).string()),
                  true);
  EXPECT_NE(r.exit_status, -1) << r.output;
  EXPECT_EQ(r.output.find("type_error"), std::string::npos) << r.output;
  std::ifstream in(jsonl);
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;
  }
  EXPECT_GE(lines, 1);
}

TEST(CliJsonFaults, AModelFolderNameThatIsNotUtf8GivesAValidJsonLeaderboard) {
  const test::TempDir dir("cli-json-folder");
  test::write_json(dir.path() / "acme\xff" / "agent" / "uav" / "sc-0000-ep-00.json", test::make_episode());
  const auto r = run_command(a3rig() + " score -q --format json " + quote(dir.path().string()));
  EXPECT_EQ(r.exit_status, 0) << r.output;
  nlohmann::json board;
  ASSERT_NO_THROW(board = nlohmann::json::parse(r.output)) << r.output;
  ASSERT_EQ(board.size(), 1u);
  EXPECT_NE(board[0].dump().find("acme\xef\xbf\xbd"), std::string::npos) << board.dump();
}

}  // namespace
}  // namespace a3
