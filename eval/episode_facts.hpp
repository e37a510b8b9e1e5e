// What the α³ pillars read from one episode, extracted once from its JSON so that scoring
// never touches the document again (and tests can build episodes directly).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace a3::eval {

enum class Speaker { kAgent, kUser, kOther };

struct TurnFacts {
  Speaker speaker = Speaker::kOther;
  int structured_actions = 0;   // MCP + A2A actions of the turn
  int matched_actions = 0;      // actions answered by a matching observation (TC)
  int observations = 0;
  // The turn's 6G vector n_t.
  std::string slice;
  double lat_ms = 0.0;
  double loss_pct = 0.0;
  double throughput_mbps = 0.0;
  double edge_load = 0.0;
};

struct EpisodeFacts {
  std::vector<TurnFacts> turns;
  bool success = false;
  // final_state
  double final_x_m = 0.0;
  double final_y_m = 0.0;
  double final_z_m = 0.0;
  double alt_min_m = 0.0;
  double alt_max_m = 0.0;
  bool nfz_violation = false;
  bool separation_breach = false;
  double battery_pct = 100.0;
  // final_state.uav.landed.site is "home": the rig says the vehicle ended landed where it took
  // off. Corpus episodes never carry it. The scorer checks it against the poses below.
  bool claims_landed_at_home = false;
  // initial_state.uav.pose x, y: home, where the vehicle took off (has_home: both are numbers).
  bool has_home = false;
  double home_x_m = 0.0;
  double home_y_m = 0.0;
  // _meta
  double gen_time_s = 0.0;
  double total_tokens = 0.0;
  int64_t attempts_used = 1;
};

}  // namespace a3::eval
