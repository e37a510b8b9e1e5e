// The two scoring profiles.
#include "eval/scoring_profile.hpp"

#include <stdexcept>

namespace a3::eval {

ScoringProfile release_profile() {
  ScoringProfile p;
  p.name = "release";
  p.description =
      "reproduces the α³-Bench public release leaderboard (B_tok=3000, B_tool=10, T_opt=10)";
  return p;
}

ScoringProfile paper_profile() {
  ScoringProfile p;
  p.name = "paper";
  p.description =
      "the paper's stated budgets (B_tok=10000, B_tool=25) and T_opt = median turn count of "
      "the run's valid successful episodes";
  p.token_budget = 10000.0;
  p.tool_budget = 25.0;
  p.optimal_turns_from_median = true;
  return p;
}

std::vector<std::string> profile_names() { return {"release", "paper"}; }

ScoringProfile profile_by_name(std::string_view name) {
  if (name == "release") return release_profile();
  if (name == "paper") return paper_profile();
  throw std::invalid_argument("unknown scoring profile '" + std::string(name) +
                              "' (known: release, paper)");
}

}  // namespace a3::eval
