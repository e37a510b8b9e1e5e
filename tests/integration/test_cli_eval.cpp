// `a3rig validate` and `a3rig score` end to end: the program's output, files and exit status,
// and an independent cross-check against the Python reference scorer (bench/eval/py_score.py,
// which validates with python3-jsonschema's Draft202012Validator).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <sstream>

#include "tests/eval/episode_builder.hpp"
#include "tests/integration/run_command.hpp"
#include "tests/test_support.hpp"

namespace a3 {
namespace {

using test::a3rig;
using test::quote;
using test::run_command;

std::filesystem::path public_corpus() { return test::shared_dir() / "alphabench" / "eval_runs"; }

bool python_reference_available() {
  return run_command("/usr/bin/python3 -c 'import jsonschema' 2>/dev/null").exit_status == 0;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Cli, VersionAndHelp) {
  auto r = run_command(a3rig() + " --version");
  EXPECT_EQ(r.exit_status, 0);
  EXPECT_EQ(r.output.rfind("a3rig ", 0), 0u) << r.output;
  r = run_command(a3rig() + " --help");
  EXPECT_EQ(r.exit_status, 0);
  EXPECT_NE(r.output.find("score"), std::string::npos);
  EXPECT_NE(r.output.find("validate"), std::string::npos);
  r = run_command(a3rig() + " score --help");
  EXPECT_EQ(r.exit_status, 0);
  for (const char* flag : {"--budget", "--format", "--per-episode", "--plots", "--profile", "--model"}) {
    EXPECT_NE(r.output.find(flag), std::string::npos) << flag;
  }
  r = run_command(a3rig() + " validate --help");
  EXPECT_EQ(r.exit_status, 0);
  EXPECT_NE(r.output.find("--format"), std::string::npos);
}

TEST(Cli, BadFlagsAreRefusedWithAMessage) {
  auto r = run_command(a3rig() + " score --format xlsx /tmp", true);
  EXPECT_NE(r.exit_status, 0);
  EXPECT_NE(r.output.find("xlsx"), std::string::npos) << r.output;
  r = run_command(a3rig() + " score --budget -3 /tmp", true);
  EXPECT_NE(r.exit_status, 0);
  r = run_command(a3rig() + " score /no/such/folder", true);
  EXPECT_NE(r.exit_status, 0);
  EXPECT_NE(r.output.find("/no/such/folder"), std::string::npos) << r.output;
  r = run_command(a3rig() + " frobnicate", true);
  EXPECT_NE(r.exit_status, 0);
}

TEST(Cli, ScoreMatchesThePythonReferenceOnThePublicCorpus) {
  if (!std::filesystem::exists(public_corpus())) {
    GTEST_SKIP() << test::shared_missing_message(public_corpus());
  }
  if (!python_reference_available()) GTEST_SKIP() << "needs python3-jsonschema (apt-get install python3-jsonschema)";
  const test::TempDir dir("cli-cross");
  for (const std::string profile : {"release", "paper"}) {
    const auto ours = run_command(a3rig() + " score -q --format json --profile " + profile +
                                  " --per-episode " + quote((dir.path() / "ours.jsonl").string()) +
                                  " " + quote(public_corpus().string()));
    ASSERT_EQ(ours.exit_status, 0) << ours.output;
    const auto theirs = run_command("/usr/bin/python3 " +
                                    quote(std::string(A3_SOURCE_DIR) + "/bench/eval/py_score.py") +
                                    " --profile " + profile + " --per-episode " +
                                    quote((dir.path() / "theirs.jsonl").string()) + " " +
                                    quote(public_corpus().string()));
    ASSERT_EQ(theirs.exit_status, 0) << theirs.output;
    const auto rows = nlohmann::json::parse(ours.output);
    std::istringstream lines(theirs.output);
    std::string line;
    std::size_t i = 0;
    while (std::getline(lines, line)) {
      const auto ref = nlohmann::json::parse(line);
      ASSERT_LT(i, rows.size());
      const auto& row = rows[i++];
      ASSERT_EQ(row["model"], ref["model"]) << profile;
      for (const auto& [key, value] : ref.items()) {
        if (value.is_number()) {
          EXPECT_NEAR(row[key].get<double>(), value.get<double>(), 1e-12) << profile << " " << row["model"] << " " << key;
        } else if (key == "pillars") {
          for (const auto& [pillar, v] : value.items()) {
            EXPECT_NEAR(row[key][pillar].get<double>(), v.get<double>(), 1e-12) << profile << " " << pillar;
          }
        }
      }
    }
    EXPECT_EQ(i, 4u);
    // Per episode: the same 200 files in the same order, the same status and α³.
    std::ifstream a(dir.path() / "ours.jsonl"), b(dir.path() / "theirs.jsonl");
    std::string la, lb;
    std::size_t episodes = 0;
    while (std::getline(a, la) && std::getline(b, lb)) {
      const auto x = nlohmann::json::parse(la), y = nlohmann::json::parse(lb);
      ASSERT_EQ(x["file"], y["file"]);
      ASSERT_EQ(x["status"], y["status"]) << x["file"];
      if (y["status"] == "valid") {
        for (const char* k : {"TO", "SP", "TC", "IQ", "NR", "CC", "alpha3"}) {
          EXPECT_NEAR(x[k].get<double>(), y[k].get<double>(), 1e-12) << x["file"] << " " << k;
        }
      }
      ++episodes;
    }
    EXPECT_EQ(episodes, 200u);
  }
}

TEST(Cli, ScoreWritesEveryFormatPerEpisodeRowsAndPlots) {
  if (!std::filesystem::exists(public_corpus())) {
    GTEST_SKIP() << test::shared_missing_message(public_corpus());
  }
  const test::TempDir dir("cli-out");
  const std::string corpus = quote(public_corpus().string());
  auto r = run_command(a3rig() + " score -q --format csv " + corpus);
  ASSERT_EQ(r.exit_status, 0);
  EXPECT_EQ(r.output.rfind("model,domain,mean,ci95,n,success_rate,", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 5);
  r = run_command(a3rig() + " score -q --format markdown " + corpus);
  EXPECT_NE(r.output.find("| openai/chatgpt-4o-latest | uav | 0.97645 |"), std::string::npos) << r.output;
  r = run_command(a3rig() + " score " + corpus, true);  // table + summary on stderr
  EXPECT_NE(r.output.find("0.97645"), std::string::npos);
  EXPECT_NE(r.output.find("200 files (176 valid, 24 failure stubs, 0 invalid)"), std::string::npos) << r.output;

  const auto csv_path = dir.path() / "episodes.csv";
  const auto plots = dir.path() / "figures";
  r = run_command(a3rig() + " score -q --per-episode " + quote(csv_path.string()) + " --plots " +
                  quote(plots.string()) + " -o " + quote((dir.path() / "board.json").string()) +
                  " --format json " + corpus, true);
  ASSERT_EQ(r.exit_status, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir.path() / "board.json")).size(), 4u);
  const std::string csv = slurp(csv_path);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 201);
  EXPECT_EQ(csv.rfind("model,domain,file,scenario,episode,status,error,TO,SP,TC,IQ,NR,CC,alpha3,", 0), 0u);
  EXPECT_NE(csv.find(",failure_stub,"), std::string::npos);
  for (const char* png : {"mean_score.png", "alpha3_rel.png", "alpha3_per_1k_tokens_vs_mean.png",
                          "alpha3_per_second_vs_mean.png", "gen_time_and_tokens.png"}) {
    const std::string bytes = slurp(plots / png);
    ASSERT_GT(bytes.size(), 5000u) << png;
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
  }
  const std::string tsv = slurp(plots / "leaderboard.tsv");
  EXPECT_NE(tsv.find("\"openai/chatgpt-4o-latest\"\tuav\t0.9764467648859523"), std::string::npos) << tsv;
}

TEST(Cli, InvalidFilesAreListedCountedAndTheExitStatusSaysSo) {
  const test::TempDir dir("cli-bad");
  const auto m = dir.path() / "acme" / "agent" / "uav";
  test::write_json(m / "sc-0000-ep-00.json", test::make_episode());
  test::write_json(m / "sc-0001-ep-00.json", test::make_episode());
  test::write_text(m / "sc-0002-ep-00.json", "{\"dialogue\": [");
  nlohmann::json bad = test::make_episode();
  bad["dialogue"][4]["speaker"] = "assistant";
  test::write_json(m / "sc-0003-ep-00.json", bad);
  std::string huge = test::make_episode().dump();
  huge.append(2u << 20, ' ');
  test::write_text(m / "sc-0004-ep-00.json", huge);

  auto r = run_command(a3rig() + " score --max-file-mb 1 --format csv " + quote(dir.path().string()), true);
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("sc-0002-ep-00.json: (root): json-syntax:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sc-0003-ep-00.json: /dialogue/4/speaker: role:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sc-0004-ep-00.json: (root): file-size:"), std::string::npos) << r.output;
  // The rest is scored: 2 valid of 5, 3 failures.
  EXPECT_NE(r.output.find("acme/agent,uav,0.9937499999999999,0,2,1,0.6,0.4,0.4,"), std::string::npos) << r.output;

  r = run_command(a3rig() + " validate --max-file-mb 1 " + quote(m.string()), true);
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_NE(r.output.find("INVALID " + (m / "sc-0003-ep-00.json").string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find((m / "sc-0003-ep-00.json").string() + ": /dialogue/4/speaker: role: speaker 'assistant'"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("5 files: 2 valid episodes, 0 failure stubs, 3 invalid"), std::string::npos) << r.output;

  r = run_command(a3rig() + " validate --format json " + quote((m / "sc-0003-ep-00.json").string()));
  const auto row = nlohmann::json::parse(r.output);
  EXPECT_EQ(row["status"], "invalid");
  EXPECT_EQ(row["violations"][0]["path"], "/dialogue/4/speaker");
  EXPECT_EQ(row["violations"][0]["rule"], "role");

  r = run_command(a3rig() + " validate " + quote((m / "sc-0000-ep-00.json").string()), true);
  EXPECT_EQ(r.exit_status, 0) << r.output;

  const test::TempDir empty("cli-empty");
  r = run_command(a3rig() + " score " + quote(empty.path().string()), true);
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.output.find("no episode files found"), std::string::npos) << r.output;
}

TEST(Cli, ValidateAcceptsThePublicCorpus) {
  if (!std::filesystem::exists(public_corpus())) {
    GTEST_SKIP() << test::shared_missing_message(public_corpus());
  }
  const auto r = run_command(a3rig() + " validate -q " + quote(public_corpus().string()), true);
  EXPECT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("200 files: 176 valid episodes, 24 failure stubs, 0 invalid"), std::string::npos)
      << r.output;
}

// Issue 34: a run folder and a sweep-like folder of a3rig's own episode.json files score as a
// user expects: one row per agent configuration, named from the files, budget scenarios x seeds.
TEST(Cli, ScoreReadsRunAndSweepFolders) {
  const test::TempDir dir("cli-score-runs");
  const auto fly = [&](const std::string& name, const std::string& flags) {
    const auto r = run_command(a3rig() + " run -q --runtime virtual --scenario traffic-conflict --out " +
                               quote((dir.path() / name).string()) + " " + flags);
    ASSERT_EQ(r.exit_status, 0) << r.output;
  };
  fly("seed-1", "--seed 1");
  auto r = run_command(a3rig() + " score -q --format json " + quote((dir.path() / "seed-1").string()));
  ASSERT_EQ(r.exit_status, 0) << r.output;
  nlohmann::json rows = nlohmann::json::parse(r.output);
  ASSERT_EQ(rows.size(), 1u) << r.output;
  EXPECT_EQ(rows[0]["model"], "a3rig/scripted");
  EXPECT_EQ(rows[0]["budget"], 1);
  EXPECT_EQ(rows[0]["n"], 1);

  fly("seed-2", "--seed 2");
  fly("slow", "--seed 1 --think-time 30 --slice URLLC");
  r = run_command(a3rig() + " score --format json " + quote(dir.path().string()), true);
  ASSERT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("budget 2 (1 scenarios x 2 episodes each)"), std::string::npos) << r.output;
  rows = nlohmann::json::parse(r.output.substr(0, r.output.find("a3rig score:")));
  ASSERT_EQ(rows.size(), 2u) << r.output;
  std::map<std::string, nlohmann::json> by_model;
  for (const auto& row : rows) by_model[row["model"]] = row;
  ASSERT_TRUE(by_model.count("a3rig/scripted")) << r.output;
  ASSERT_TRUE(by_model.count("a3rig/scripted, think 30, URLLC")) << r.output;
  EXPECT_EQ(by_model["a3rig/scripted"]["files"], 2);
  EXPECT_EQ(by_model["a3rig/scripted, think 30, URLLC"]["files"], 1);
}

}  // namespace
}  // namespace a3
