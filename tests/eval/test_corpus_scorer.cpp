// The scoring pipeline on corpora made here: attribution to models, bad files counted as
// failures while the rest is scored, deterministic results whatever the thread count, and
// batches larger than one.
#include <gtest/gtest.h>

#include <map>

#include "eval/corpus_scorer.hpp"
#include "eval/episode_schema.hpp"
#include "tests/eval/episode_builder.hpp"

namespace a3::eval {
namespace {

namespace fs = std::filesystem;
using a3::test::make_episode;
using a3::test::write_json;
using a3::test::write_text;

std::string file_name(int scenario, int episode) {
  char name[64];
  std::snprintf(name, sizeof name, "sc-%04d-ep-%02d.json", scenario, episode);
  return name;
}

class CorpusScorerTest : public ::testing::Test {
 protected:
  CorpusScorerTest() : dir_("scorer") {}

  const ModelSummary* find(const ScoreResult& r, const std::string& model) {
    for (const auto& m : r.models) {
      if (m.model == model) return &m;
    }
    return nullptr;
  }

  a3::test::TempDir dir_;
  const JsonSchemaValidator validator_{episode_schema_json(), kEpisodeSchemaName};
};

TEST_F(CorpusScorerTest, BadFilesAreCountedAndTheRestIsScored) {
  const fs::path good = dir_.path() / "acme" / "good-model" / "uav";
  const fs::path mixed = dir_.path() / "acme" / "mixed-model" / "uav";
  for (int sc = 0; sc < 4; ++sc) write_json(good / file_name(sc, 0), make_episode());
  write_json(mixed / file_name(0, 0), make_episode());
  write_json(mixed / file_name(1, 0), a3::test::make_failure_stub());
  write_text(mixed / file_name(2, 0), "{\"initial_state\": {\"domain\": ");  // truncated
  nlohmann::json wrong = make_episode();
  wrong["dialogue"][0]["net"]["loss_pct"] = "high";
  wrong["_meta"]["attempts_used"] = 2;
  write_json(mixed / file_name(3, 0), wrong);
  write_text(mixed / "notes.json", "{}");  // not an episode name: ignored, counted
  write_text(mixed / "README.txt", "hello");

  std::vector<std::string> seen;
  ScoreOptions options;
  options.on_episode = [&](const ScoredEpisode& e) {
    seen.push_back(e.file.path.filename().string() + ":" + to_string(e.check.status));
    EXPECT_EQ(e.pillars != nullptr, e.check.status == EpisodeStatus::kValid);
  };
  const ScoreResult r = score_corpus({dir_.path()}, validator_, options);
  EXPECT_EQ(r.files, 8u);
  EXPECT_EQ(r.valid, 5u);
  EXPECT_EQ(r.failure_stubs, 1u);
  EXPECT_EQ(r.invalid, 2u);
  EXPECT_EQ(r.ignored_json_files, 1u);
  EXPECT_EQ(r.scenarios_found, 4);
  EXPECT_EQ(r.budget, 4);
  // Corpus order: folders and files sorted.
  const std::vector<std::string> expected = {
      "sc-0000-ep-00.json:valid",   "sc-0001-ep-00.json:valid",
      "sc-0002-ep-00.json:valid",   "sc-0003-ep-00.json:valid",
      "sc-0000-ep-00.json:valid",   "sc-0001-ep-00.json:failure_stub",
      "sc-0002-ep-00.json:invalid", "sc-0003-ep-00.json:invalid"};
  EXPECT_EQ(seen, expected);

  const ModelSummary* g = find(r, "acme/good-model");
  const ModelSummary* m = find(r, "acme/mixed-model");
  ASSERT_TRUE(g && m);
  EXPECT_EQ(g->n, 4);
  EXPECT_DOUBLE_EQ(g->reliability, 1.0);
  EXPECT_DOUBLE_EQ(g->coverage, 1.0);
  EXPECT_EQ(m->n, 1);
  EXPECT_EQ(m->n_fail, 3);
  EXPECT_EQ(m->n_invalid, 2);
  EXPECT_DOUBLE_EQ(m->reliability, 0.25);
  EXPECT_DOUBLE_EQ(m->coverage, 0.25);
  EXPECT_EQ(m->total_attempt_calls, 1 + 1 + 1 + 2);
  EXPECT_DOUBLE_EQ(m->call_efficiency, 4.0 / 5.0);
  EXPECT_DOUBLE_EQ(m->gen_fail_rate, 0.75);
  EXPECT_EQ(r.models.front().model, "acme/good-model");  // best alpha3_rel first
}

TEST_F(CorpusScorerTest, FlatFolderWithModelOverrideAndExplicitBudget) {
  for (int sc = 0; sc < 3; ++sc) {
    for (int ep = 0; ep < 2; ++ep) write_json(dir_.path() / file_name(sc, ep), make_episode());
  }
  ScoreOptions options;
  options.corpus.model_override = "local/my-agent";
  options.corpus.domain_override = "uav";
  ScoreResult r = score_corpus({dir_.path()}, validator_, options);
  ASSERT_EQ(r.models.size(), 1u);
  EXPECT_EQ(r.models[0].model, "local/my-agent");
  EXPECT_EQ(r.budget, 6);  // 3 scenarios x 2 episodes
  EXPECT_DOUBLE_EQ(r.models[0].coverage, 1.0);
  options.budget = 12;
  r = score_corpus({dir_.path()}, validator_, options);
  EXPECT_DOUBLE_EQ(r.models[0].coverage, 0.5);
  EXPECT_DOUBLE_EQ(r.models[0].call_efficiency, 1.0);
}

TEST_F(CorpusScorerTest, ThreadCountDoesNotChangeAnyResultAndBatchesChain) {
  // 2600 files: more than two batches of 1024. Vary the episodes so the sums are not trivial.
  const fs::path model_dir = dir_.path() / "p" / "m" / "uav";
  for (int i = 0; i < 2600; ++i) {
    nlohmann::json e = make_episode(8 + i % 5);
    e["_meta"]["usage"]["total_tokens"] = 1000 + 37 * i;
    e["_meta"]["gen_time_s"] = 0.1 * (i % 97);
    e["dialogue"][1]["net"]["lat_ms"] = i % 3 == 0 ? 90.0 : 9.0;
    e["success"] = i % 7 != 0;
    if (i % 50 == 0) e["dialogue"][0]["speaker"] = "system";  // invalid
    write_json(model_dir / file_name(i / 10, i % 10), e);
  }
  std::vector<std::vector<double>> alphas;
  std::vector<ModelSummary> rows;
  for (std::size_t threads : {1u, 2u, 4u}) {
    ScoreOptions options;
    options.threads = threads;
    std::vector<double> per_episode;
    options.on_episode = [&](const ScoredEpisode& e) {
      per_episode.push_back(e.pillars ? e.pillars->alpha3 : -1.0);
    };
    const ScoreResult r = score_corpus({dir_.path()}, validator_, options);
    EXPECT_EQ(r.files, 2600u);
    EXPECT_EQ(r.invalid, 52u);
    ASSERT_EQ(r.models.size(), 1u);
    rows.push_back(r.models[0]);
    alphas.push_back(per_episode);
  }
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_EQ(alphas[k], alphas[0]);
    // Bitwise identical aggregates.
    EXPECT_EQ(rows[k].mean, rows[0].mean);
    EXPECT_EQ(rows[k].ci95, rows[0].ci95);
    EXPECT_EQ(rows[k].pillars.nr, rows[0].pillars.nr);
    EXPECT_EQ(rows[k].mean_total_tokens, rows[0].mean_total_tokens);
    EXPECT_EQ(rows[k].alpha3_rel, rows[0].alpha3_rel);
  }
  EXPECT_EQ(rows[0].n, 2548);
  EXPECT_NEAR(rows[0].success_rate, 1.0 - 372.0 / 2548.0, 0.01);
}

TEST_F(CorpusScorerTest, ProgressIsReportedPerBatch) {
  for (int i = 0; i < 1500; ++i) write_json(dir_.path() / "p" / "m" / "uav" / file_name(i, 0), make_episode());
  std::vector<uint64_t> done;
  ScoreOptions options;
  options.on_progress = [&](const ScoreProgress& p) { done.push_back(p.files_done); };
  score_corpus({dir_.path()}, validator_, options);
  EXPECT_EQ(done, (std::vector<uint64_t>{1024, 1500}));
}

TEST_F(CorpusScorerTest, MissingRootIsAClearError) {
  try {
    score_corpus({dir_.path() / "nope"}, validator_, ScoreOptions{});
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos);
  }
}

TEST_F(CorpusScorerTest, CheckCorpusVisitsEveryFileInOrder) {
  write_json(dir_.path() / "a" / "b" / "c" / file_name(1, 0), make_episode());
  write_text(dir_.path() / "a" / "b" / "c" / file_name(0, 0), "[]");
  std::vector<std::string> seen;
  const CheckSummary s = check_corpus({dir_.path()}, validator_, 2, 1 << 20,
                                      [&](const EpisodeFile& f, const EpisodeCheck& c) {
                                        seen.push_back(f.path.filename().string() + ":" +
                                                       to_string(c.status));
                                      });
  EXPECT_EQ(s.files, 2u);
  EXPECT_EQ(seen, (std::vector<std::string>{"sc-0000-ep-00.json:invalid", "sc-0001-ep-00.json:valid"}));
}

}  // namespace
}  // namespace a3::eval
