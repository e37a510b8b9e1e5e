// LatencyModel: each spec form gives the latency it promises, scaled; bad specs are named.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>

#include "agent/conversation/think_time.hpp"
#include "agent/model_server/latency_model.hpp"

namespace {

using a3::agent::model_server::LatencyModel;
using a3::agent::model_server::ResponderReply;
using a3::common::Rng;

ResponderReply reply_with(std::optional<double> latency_s, int prompt_tokens = 0, int completion_tokens = 0) {
  ResponderReply r;
  r.latency_s = latency_s;
  r.usage = {{"prompt_tokens", prompt_tokens}, {"completion_tokens", completion_tokens}};
  return r;
}

double profile_mean_s(const std::string& name) {
  for (const auto& p : a3::agent::model_latency_profiles()) {
    if (p.name == name) return p.mean_generation_time_s;
  }
  return NAN;
}

TEST(LatencyModel, RecordedIsTheRespondersLatencyTimesTheScale) {
  Rng rng(1);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("recorded").latency_s(reply_with(12.5), rng), 12.5);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("recorded", 0.1).latency_s(reply_with(12.5), rng), 1.25);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("recorded").latency_s(reply_with(std::nullopt), rng), 0.0);
  EXPECT_FALSE(LatencyModel::parse("recorded").mean_s().has_value());
}

TEST(LatencyModel, FixedAndPlainSecondsAreScaledToo) {
  Rng rng(1);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("fixed:2").latency_s(reply_with(99.0), rng), 2.0);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("0.75").latency_s(reply_with(std::nullopt), rng), 0.75);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("fixed:2", 0.5).latency_s(reply_with(std::nullopt), rng), 1.0);
  EXPECT_DOUBLE_EQ(*LatencyModel::parse("fixed:2", 3.0).mean_s(), 6.0);
}

TEST(LatencyModel, ModelProfileIsPerTurnAndModelEpisodeIsPerEpisode) {
  const double episode_mean_s = profile_mean_s("GPT-4.1-mini");
  ASSERT_TRUE(std::isfinite(episode_mean_s));
  const LatencyModel turn = LatencyModel::parse("model:GPT-4.1-mini");
  const LatencyModel episode = LatencyModel::parse("model-episode:GPT-4.1-mini");
  EXPECT_NEAR(*turn.mean_s(), a3::agent::ThinkTime::parse("model:GPT-4.1-mini").mean_s(), 1e-12);
  EXPECT_NEAR(*episode.mean_s(), episode_mean_s, 1e-9);
  EXPECT_GT(*episode.mean_s(), 3.0 * *turn.mean_s());  // an episode is several turns

  Rng rng(7);
  double sum_s = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) sum_s += episode.latency_s(reply_with(std::nullopt), rng);
  EXPECT_NEAR(sum_s / n, episode_mean_s, 0.03 * episode_mean_s);
}

TEST(LatencyModel, ModelNamesIgnoreCase) {
  const double turn_mean_s = a3::agent::ThinkTime::parse("model:Claude-Haiku-4.5").mean_s();
  EXPECT_GT(turn_mean_s, 0.0);
  EXPECT_DOUBLE_EQ(a3::agent::ThinkTime::parse("model:claude-haiku-4.5").mean_s(), turn_mean_s);
  EXPECT_NEAR(*LatencyModel::parse("model-episode:gpt-4.1-mini").mean_s(), profile_mean_s("GPT-4.1-mini"), 1e-9);
  EXPECT_THROW(a3::agent::ThinkTime::parse("model:claude-haiku"), std::invalid_argument);
}

TEST(LatencyModel, SameSeedSameDraws) {
  const LatencyModel m = LatencyModel::parse("lognormal:2,0.5");
  Rng a(42), b(42), c(43);
  const double first = m.latency_s(reply_with(std::nullopt), a);
  EXPECT_EQ(first, m.latency_s(reply_with(std::nullopt), b));
  EXPECT_NE(first, m.latency_s(reply_with(std::nullopt), c));
}

TEST(LatencyModel, TokensFormUsesTheReplysTokenCounts) {
  Rng rng(1);
  const LatencyModel m = LatencyModel::parse("tokens:1000,50,0.25");
  // 0.25 + 2000/1000 + 100/50 = 4.25
  EXPECT_DOUBLE_EQ(m.latency_s(reply_with(std::nullopt, 2000, 100), rng), 4.25);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("tokens:1000,50").latency_s(reply_with(std::nullopt, 2000, 100), rng), 4.0);
  EXPECT_DOUBLE_EQ(LatencyModel::parse("tokens:1000,50", 0.5).latency_s(reply_with(std::nullopt, 2000, 100), rng), 2.0);
}

TEST(LatencyModel, BadSpecsAreNamed) {
  auto error_of = [](const std::string& spec, double scale = 1.0) {
    try {
      LatencyModel::parse(spec, scale);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("sometimes").find("sometimes"), std::string::npos);
  EXPECT_NE(error_of("sometimes").find("tokens:"), std::string::npos);
  EXPECT_NE(error_of("model:GPT-9").find("unknown model"), std::string::npos);
  EXPECT_NE(error_of("model-episode:GPT-9").find("unknown model"), std::string::npos);
  EXPECT_NE(error_of("tokens:1000").find("PREFILL"), std::string::npos);
  EXPECT_NE(error_of("tokens:0,50").find("> 0"), std::string::npos);
  EXPECT_NE(error_of("tokens:abc,50").find("'abc' is not a number"), std::string::npos);
  EXPECT_NE(error_of("fixed:1", -1.0).find("time scale"), std::string::npos);
}

TEST(LatencyModel, DescribeSaysWhatItDoes) {
  EXPECT_NE(LatencyModel::parse("recorded", 0.1).describe().find("time scale 0.1"), std::string::npos);
  EXPECT_NE(LatencyModel::parse("model-episode:GPT-4.1-mini").describe().find("mean 78.3 s"), std::string::npos);
  EXPECT_NE(LatencyModel::parse("tokens:2000,40,0.3").describe().find("decode 40 tok/s"), std::string::npos);
}

}  // namespace
