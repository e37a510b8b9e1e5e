// The calibration target of SPEC §5: scoring the public α³-Bench episodes with the `release`
// profile reproduces the published leaderboard row of openai/chatgpt-4o-latest, and the same
// code (no special case) scores the three other public models, failure stubs included.
// Needs ../shared/alphabench (the α³-Bench public release); skipped without it.
#include <gtest/gtest.h>

#include <map>

#include "eval/corpus_scorer.hpp"
#include "eval/episode_schema.hpp"
#include "tests/test_support.hpp"

namespace a3::eval {
namespace {

constexpr double kExact = 1e-9;
constexpr double kPrinted = 0.5e-5 + 1e-12;  // SPEC §5 prints 5 decimals

class PublicCorpus : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto root = a3::test::shared_dir() / "alphabench" / "eval_runs";
    if (!std::filesystem::exists(root)) return;
    const JsonSchemaValidator validator(episode_schema_json(), kEpisodeSchemaName);
    ScoreOptions options;
    options.budget = 50;
    result_ = new ScoreResult(score_corpus({root}, validator, options));
  }
  static void TearDownTestSuite() {
    delete result_;
    result_ = nullptr;
  }
  void SetUp() override {
    if (result_ == nullptr) {
      GTEST_SKIP() << a3::test::shared_missing_message(a3::test::shared_dir() / "alphabench");
    }
  }
  static const ModelSummary& model(const std::string& name) {
    for (const auto& m : result_->models) {
      if (m.model == name) return m;
    }
    throw std::runtime_error("model not scored: " + name);
  }
  static ScoreResult* result_;
};
ScoreResult* PublicCorpus::result_ = nullptr;

TEST_F(PublicCorpus, ChatGpt4oReproducesThePublishedRow) {
  const ModelSummary& m = model("openai/chatgpt-4o-latest");
  EXPECT_EQ(m.domain, "uav");
  // The published values (SPEC §5) at their printed precision...
  EXPECT_EQ(m.n, 50);
  EXPECT_NEAR(m.mean, 0.97645, kPrinted);
  EXPECT_NEAR(m.success_rate, 1.0, kExact);
  EXPECT_NEAR(m.gen_fail_rate, 0.0, kExact);
  EXPECT_NEAR(m.reliability, 1.0, kExact);
  EXPECT_NEAR(m.coverage, 1.0, kExact);
  EXPECT_NEAR(m.call_efficiency, 1.0, kExact);
  EXPECT_NEAR(m.alpha3_rel, 0.97645, kPrinted);
  EXPECT_NEAR(m.pillars.to, 1.0, kExact);
  EXPECT_NEAR(m.pillars.sp, 0.99, kExact);
  EXPECT_NEAR(m.pillars.tc, 1.0, kExact);
  EXPECT_NEAR(m.pillars.iq, 0.99495, kPrinted);
  EXPECT_NEAR(m.pillars.nr, 0.85522, kPrinted);
  EXPECT_NEAR(m.pillars.cc, 0.87365, kPrinted);
  EXPECT_NEAR(m.mean_gen_time_s, 10.58062, kPrinted);
  EXPECT_NEAR(m.mean_total_tokens, 4032.1, kExact);
  EXPECT_NEAR(m.alpha3_per_second, 0.09229, kPrinted);
  EXPECT_NEAR(m.alpha3_per_1k_tokens, 0.24217, kPrinted);
  EXPECT_EQ(m.total_attempt_calls, 50);
  // ...and to 1e-9 in every field, against the full-precision values (the public release's
  // numbers, which an independent Python implementation of the same rules reproduces too).
  EXPECT_NEAR(m.mean, 0.9764467648859523, kExact);
  EXPECT_NEAR(m.ci95, 0.0036220252165312964, kExact);
  EXPECT_NEAR(m.alpha3_rel, 0.9764467648859523, kExact);
  EXPECT_NEAR(m.pillars.iq, 197.0 / 198.0, kExact);
  EXPECT_NEAR(m.pillars.nr, 0.8552207792207792, kExact);
  EXPECT_NEAR(m.pillars.cc, 0.8736452544290024, kExact);
  EXPECT_NEAR(m.mean_gen_time_s, 10.58061728000641, kExact);
  EXPECT_NEAR(m.alpha3_per_second, 0.09228637035488356, kExact);
  EXPECT_NEAR(m.alpha3_per_1k_tokens, 0.24216829068871118, kExact);
  EXPECT_NEAR(m.mean_attempts_used, 1.0, kExact);
}

TEST_F(PublicCorpus, FailureStubsCountAgainstReliabilityCoverageAndCallEfficiency) {
  const ModelSummary& m = model("google/gemini-3-pro-preview");
  EXPECT_EQ(m.files, 50);
  EXPECT_EQ(m.n, 26);
  EXPECT_EQ(m.n_fail, 24);
  EXPECT_EQ(m.n_invalid, 0);
  EXPECT_NEAR(m.gen_fail_rate, 24.0 / 50.0, kExact);
  EXPECT_NEAR(m.reliability, 26.0 / 50.0, kExact);
  EXPECT_NEAR(m.coverage, 26.0 / 50.0, kExact);
  // Stubs have no attempts_used and count one call each.
  EXPECT_EQ(m.total_attempt_calls, 74);
  EXPECT_NEAR(m.call_efficiency, 50.0 / 74.0, kExact);
  EXPECT_NEAR(m.mean, 0.9518008297455028, kExact);
  EXPECT_NEAR(m.alpha3_rel, 0.9518008297455028 * 0.52 * 0.52 * (50.0 / 74.0), kExact);
  EXPECT_NEAR(m.mean_total_tokens, 7526.192307692308, kExact);
}

TEST_F(PublicCorpus, RetriesLowerCallEfficiency) {
  const ModelSummary& haiku = model("anthropic/claude-haiku-4.5");
  EXPECT_EQ(haiku.total_attempt_calls, 56);
  EXPECT_NEAR(haiku.call_efficiency, 50.0 / 56.0, kExact);
  EXPECT_NEAR(haiku.mean, 0.931025671823399, kExact);
  EXPECT_NEAR(haiku.pillars.iq, 0.9444444444444445, kExact);  // longer dialogues
  EXPECT_NEAR(haiku.pillars.cc, 0.47292969038949634, kExact);
  const ModelSummary& gpt51 = model("openai/gpt-5.1-chat");
  EXPECT_EQ(gpt51.total_attempt_calls, 60);
  EXPECT_NEAR(gpt51.alpha3_rel, 0.8254345487394014, kExact);
  EXPECT_NEAR(gpt51.pillars.nr, 0.9174507936507936, kExact);
}

TEST_F(PublicCorpus, EveryPublicFileIsValidOrAStubAndTheLeaderboardIsSorted) {
  EXPECT_EQ(result_->files, 200u);
  EXPECT_EQ(result_->valid, 176u);
  EXPECT_EQ(result_->failure_stubs, 24u);
  EXPECT_EQ(result_->invalid, 0u);
  EXPECT_EQ(result_->scenarios_found, 50);
  EXPECT_EQ(result_->episodes_per_scenario, 1);
  ASSERT_EQ(result_->models.size(), 4u);
  for (std::size_t i = 1; i < result_->models.size(); ++i) {
    EXPECT_GE(result_->models[i - 1].alpha3_rel, result_->models[i].alpha3_rel);
  }
  EXPECT_EQ(result_->models.front().model, "openai/chatgpt-4o-latest");
}

TEST_F(PublicCorpus, DefaultBudgetIsScenariosTimesEpisodes) {
  const auto root = a3::test::shared_dir() / "alphabench" / "eval_runs";
  const JsonSchemaValidator validator(episode_schema_json(), kEpisodeSchemaName);
  const ScoreResult r = score_corpus({root}, validator, ScoreOptions{});
  EXPECT_EQ(r.budget, 50);
  for (const auto& m : r.models) EXPECT_EQ(m.budget, 50);
}

TEST_F(PublicCorpus, PaperProfileUsesItsBudgetsAndTheMedianTurnCount) {
  const auto root = a3::test::shared_dir() / "alphabench" / "eval_runs";
  const JsonSchemaValidator validator(episode_schema_json(), kEpisodeSchemaName);
  ScoreOptions options;
  options.profile = paper_profile();
  const ScoreResult r = score_corpus({root}, validator, options);
  // T in the public corpus: 49×8, 14×9, 47×10, 12×11, 54×12 valid and successful -> median 10.
  EXPECT_DOUBLE_EQ(r.optimal_turns, 10.0);
  for (const auto& m : r.models) {
    const ModelSummary& release = model(m.model);
    EXPECT_GE(m.pillars.cc, release.pillars.cc) << m.model;  // larger budgets
    EXPECT_NEAR(m.pillars.iq, release.pillars.iq, kExact) << m.model;  // same T_opt here
  }
  // Every public episode is under 10 000 tokens and 25 tool calls: CC = 1 for all.
  for (const auto& m : r.models) EXPECT_NEAR(m.pillars.cc, 1.0, kExact) << m.model;
  EXPECT_EQ(r.models.front().model, "openai/chatgpt-4o-latest");
  EXPECT_NEAR(r.models.front().mean, 0.9827645021645022, kExact);
}

}  // namespace
}  // namespace a3::eval
