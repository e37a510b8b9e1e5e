// Leaderboard output: the release's columns in every format, full precision in CSV and JSON.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <sstream>

#include "eval/leaderboard_format.hpp"

namespace a3::eval {
namespace {

ModelSummary row(const std::string& model, double mean) {
  ModelSummary s;
  s.model = model;
  s.domain = "uav";
  s.mean = mean;
  s.ci95 = 0.003622025216531289;
  s.n = 50;
  s.success_rate = 1.0;
  s.reliability = 1.0;
  s.coverage = 1.0;
  s.alpha3_rel = mean;
  s.pillars = {1.0, 0.99, 1.0, 0.9949494949494948, 0.8552207792207792, 0.8736452544290022};
  s.mean_gen_time_s = 10.58061728000641;
  s.mean_total_tokens = 4032.1;
  s.alpha3_per_second = 0.09228637035488356;
  s.alpha3_per_1k_tokens = 0.24216829068871118;
  s.total_attempt_calls = 50;
  s.mean_attempts_used = 1.0;
  s.call_efficiency = 1.0;
  s.files = 50;
  s.budget = 50;
  return s;
}

std::string render(LeaderboardFormat format) {
  std::ostringstream out;
  write_leaderboard(out, {row("openai/chatgpt-4o-latest", 0.9764467648859523),
                          row("team, \"quoted\"/model", 0.5)},
                    format);
  return out.str();
}

TEST(LeaderboardFormat, ColumnsAreTheReleaseColumnsInOrder) {
  const std::vector<std::string> expected = {
      "model", "domain", "mean", "ci95", "n", "success_rate", "gen_fail_rate", "reliability",
      "coverage", "alpha3_rel", "pillars", "mean_gen_time_s", "mean_total_tokens",
      "alpha3_per_second", "alpha3_per_1k_tokens", "total_attempt_calls", "mean_attempts_used",
      "call_efficiency"};
  EXPECT_EQ(leaderboard_columns(), expected);
}

TEST(LeaderboardFormat, CsvHasHeaderFullPrecisionAndQuoting) {
  const std::string csv = render(LeaderboardFormat::kCsv);
  std::istringstream lines(csv);
  std::string header, first, second;
  std::getline(lines, header);
  std::getline(lines, first);
  std::getline(lines, second);
  EXPECT_EQ(header,
            "model,domain,mean,ci95,n,success_rate,gen_fail_rate,reliability,coverage,alpha3_rel,"
            "pillars,mean_gen_time_s,mean_total_tokens,alpha3_per_second,alpha3_per_1k_tokens,"
            "total_attempt_calls,mean_attempts_used,call_efficiency");
  EXPECT_EQ(first.rfind("openai/chatgpt-4o-latest,uav,0.9764467648859523,", 0), 0u) << first;
  EXPECT_NE(first.find("\"{\"\"TO\"\":1,\"\"SP\"\":0.99,"), std::string::npos) << first;
  EXPECT_EQ(second.rfind("\"team, \"\"quoted\"\"/model\",uav,0.5,", 0), 0u) << second;
}

TEST(LeaderboardFormat, JsonRoundTripsEveryValue) {
  const auto j = nlohmann::ordered_json::parse(render(LeaderboardFormat::kJson));
  ASSERT_EQ(j.size(), 2u);
  EXPECT_EQ(j[0]["model"], "openai/chatgpt-4o-latest");
  EXPECT_EQ(j[0]["mean"].get<double>(), 0.9764467648859523);
  EXPECT_EQ(j[0]["pillars"]["NR"].get<double>(), 0.8552207792207792);
  EXPECT_EQ(j[0]["mean_total_tokens"].get<double>(), 4032.1);
  EXPECT_EQ(j[0]["total_attempt_calls"].get<int>(), 50);
  std::vector<std::string> keys;
  for (const auto& [key, value] : j[0].items()) keys.push_back(key);
  // The release's columns come first and in order; extras follow.
  const auto& columns = leaderboard_columns();
  ASSERT_GE(keys.size(), columns.size());
  for (std::size_t i = 0; i < columns.size(); ++i) EXPECT_EQ(keys[i], columns[i]);
}

TEST(LeaderboardFormat, MarkdownAndTableRoundToFiveDecimals) {
  const std::string md = render(LeaderboardFormat::kMarkdown);
  EXPECT_EQ(md.rfind("| model | domain | mean |", 0), 0u) << md;
  EXPECT_NE(md.find("| openai/chatgpt-4o-latest | uav | 0.97645 | 0.00362 | 50 |"),
            std::string::npos)
      << md;
  const std::string table = render(LeaderboardFormat::kTable);
  EXPECT_NE(table.find("0.97645"), std::string::npos);
  EXPECT_NE(table.find("10.58062"), std::string::npos);
  EXPECT_EQ(table.find("0.9764467"), std::string::npos);
  // Every line of the table has the same column layout: 3 lines.
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3);
}

TEST(LeaderboardFormat, ParseFormatNames) {
  EXPECT_EQ(parse_leaderboard_format("csv"), LeaderboardFormat::kCsv);
  EXPECT_EQ(parse_leaderboard_format("markdown"), LeaderboardFormat::kMarkdown);
  EXPECT_THROW(parse_leaderboard_format("xlsx"), std::invalid_argument);
}

TEST(FormatDouble, ShortestRoundTrip) {
  for (double x : {0.1, 0.9764467648859523, 4032.1, 1e-300, 123456789.0, 1.0 / 3.0}) {
    EXPECT_EQ(std::stod(format_double(x)), x);
  }
  EXPECT_EQ(format_double(0.5), "0.5");
  EXPECT_EQ(format_double(1.0), "1");
}

}  // namespace
}  // namespace a3::eval
