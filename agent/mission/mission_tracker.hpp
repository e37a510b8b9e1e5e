// What a mission has achieved, from what really happened: image captures (payload events with
// the true position), the true trajectory, and the flight controller's state. Survey, image and
// search objectives are achieved once and stay achieved; return-and-land holds while the
// vehicle is disarmed on the ground near home. A thermal search finds its target when the
// active thermal camera passes within the objective's radius of it (at most 40 m above the
// objective's altitude), or when a thermal capture is taken there. The numbers and the sentence
// each brief states are in objective_rules.hpp.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <limits>
#include <string>
#include <vector>

#include "a3lcm/fc_status_t.hpp"
#include "a3lcm/payload_event_t.hpp"
#include "a3lcm/vehicle_state_t.hpp"
#include "agent/mission/mission.hpp"

namespace a3::agent {

struct ObjectiveProgress {
  bool done = false;
  double done_at_s = -1.0;
  int count = 0;               // captures that count (survey)
  double dwell_s = 0.0;        // delivery: time spent at the drop point without a break, now
  double longest_dwell_s = 0.0;  // ... the longest such stay so far
  double lowest_in_radius_m = std::numeric_limits<double>::infinity();  // delivery: lowest altitude there
  std::string detail;
};

class MissionTracker {
 public:
  explicit MissionTracker(Mission mission);

  void on_state(const a3lcm::vehicle_state_t& s);
  void on_fc_status(const a3lcm::fc_status_t& s);
  void on_payload(const a3lcm::payload_event_t& e);

  bool all_done() const;
  const std::vector<ObjectiveProgress>& progress() const { return progress_; }
  const Mission& mission() const { return mission_; }
  // Why a delivery that came within its radius is not done (the altitude reached, or a stay too
  // short); "" for anything else.
  std::string why_not_done(std::size_t i) const;
  // {"objectives": [{id, type, done, done_at_s, detail, why_not}], "all_done", "mode", "armed",
  //  "on_ground", "position": [x, y, z]}
  nlohmann::json to_json() const;
  // Bumped whenever an objective changes state: a cheap "did anything happen" check.
  int version() const { return version_; }
  const a3lcm::fc_status_t& fc_status() const { return fc_; }
  const a3lcm::vehicle_state_t& state() const { return state_; }

 private:
  static constexpr double kNever = std::numeric_limits<double>::infinity();
  void track_delivery(std::size_t i, const a3lcm::vehicle_state_t& s, double dt_s);
  void update_landing();
  void mark(std::size_t i, double t_s, const std::string& detail);

  Mission mission_;
  std::vector<ObjectiveProgress> progress_;
  a3lcm::vehicle_state_t state_{};
  std::vector<std::string> active_sensors_;
  a3lcm::fc_status_t fc_{};
  bool have_state_ = false;
  double last_state_t_s_ = -1.0;
  int version_ = 0;
};

}  // namespace a3::agent
