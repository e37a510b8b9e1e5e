// A mission: the objectives that decide an episode's success, in local ENU metres. Built from a
// scenario file by rigs/; read by the mission tracker (what has been achieved), the scripted
// agent (what to do) and the simulated supervisor (what to ask about).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "common/polygon.hpp"

namespace a3::agent {

enum class ObjectiveType { kSurvey, kImagePoint, kDelivery, kThermalSearch, kReturnAndLand };
const char* to_string(ObjectiveType type);

struct Objective {
  std::string id;
  ObjectiveType type = ObjectiveType::kReturnAndLand;
  std::string description;
  // survey / thermal_search: the area; image_point / delivery: the point (x, y); thermal_search:
  // the hidden target (the agent is not told where it is).
  common::Polygon2d area;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  Eigen::Vector2d hidden_target = Eigen::Vector2d::Zero();
  double radius_m = 15.0;          // image_point / delivery / return: how close counts
  double altitude_m = 60.0;        // suggested altitude
  int images_required = 4;         // survey: captures inside the area
  std::string sensor = "rgb";      // image_point / survey / thermal_search
  double drop_altitude_m = 10.0;   // delivery: at or below this altitude over the point
};

struct Mission {
  std::string name;
  std::string description;        // what the supervisor asks for, in words
  std::vector<Objective> objectives;
  Eigen::Vector3d home_W_m = Eigen::Vector3d::Zero();
  double cruise_altitude_m = 60.0;
  double cruise_speed_mps = 8.0;
  double time_limit_s = 900.0;     // the episode ends at this mission time at the latest
};

// The objectives as JSON, for prompts and the episode (hidden targets left out).
nlohmann::json mission_brief_json(const Mission& mission);

}  // namespace a3::agent
