// The drawn layout of a generated mission (before it becomes a scenario document): geofence,
// home, objectives in flying order, no-fly zones across the route, crossing traffic, weather,
// payloads and the network script. Each part draws from its own named stream of the seed
// (and the attempt), so a knob changes only what it is about.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "agent/mission/mission.hpp"
#include "common/polygon.hpp"
#include "rigs/generator/scenario_generator_knobs.hpp"

namespace a3::rigs {

struct DrawnObjective {
  std::string id;
  agent::ObjectiveType type = agent::ObjectiveType::kImagePoint;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();   // image_point, delivery
  common::Polygon2d area;                            // survey, thermal_search (rectangle, counter-clockwise)
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  // thermal_search
  double radius_m = 15.0;
  double altitude_m = 60.0;
  int images_required = 4;
  double drop_altitude_m = 8.0;
  std::string sensor = "rgb";
};

struct Layout {
  common::Polygon2d geofence;
  Eigen::Vector2d home = Eigen::Vector2d::Zero();
  double home_yaw_deg = 90.0;
  double max_altitude_m = 120.0;
  double cruise_altitude_m = 60.0;
  double cruise_speed_mps = 8.0;
  std::string airframe = "iris";
  std::vector<DrawnObjective> objectives;  // without the final return_and_land
  nlohmann::json zones = nlohmann::json::array();
  nlohmann::json traffic = nlohmann::json::array();
  nlohmann::json env = nlohmann::json::object();
  nlohmann::json payloads = nlohmann::json::array();
  nlohmann::json network = nlohmann::json::object();
};

// The agent turns an objective takes with the reference policy (an image point: fly, then capture).
int objective_steps(agent::ObjectiveType type);

// One draw; nothing (with *problem set) when rejection sampling found no place for a part.
std::optional<Layout> draw_layout(const GeneratorSpec& spec, const std::string& airframe, int attempt,
                                  std::string* problem);

}  // namespace a3::rigs
