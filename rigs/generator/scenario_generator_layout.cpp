// Rejection sampling of a mission layout.
#include "rigs/generator/scenario_generator_layout.hpp"

#include <algorithm>
#include <cmath>

#include "common/json_file.hpp"
#include "common/rng.hpp"
#include "linkemu/network_state.hpp"
#include "rigs/generator/scenario_generator_check.hpp"
#include "vehicle/maneuvers.hpp"

namespace a3::rigs {
namespace {

using agent::ObjectiveType;
using common::Rng;
using Vec = Eigen::Vector2d;

constexpr int kPlacementTries = 200;
constexpr double kFenceMargin_m = 80.0;      // objectives from the geofence
constexpr double kObjectiveGap_m = 100.0;    // between objectives
constexpr double kZoneMargin_m = 50.0;       // zones from home and objectives
constexpr double kZoneFenceGap_m = 70.0;     // room to pass a zone inside the fence
constexpr double kTrafficHorizon_s = 1800.0; // the patrols' planned paths run this long

double round1(double x) { return std::round(x); }
Vec round_xy(const Vec& p) { return {round1(p.x()), round1(p.y())}; }

template <typename T>
const T& pick(Rng& rng, const std::vector<T>& items) {
  return items[static_cast<std::size_t>(rng.uniform01() * static_cast<double>(items.size()))];
}

std::string kind_prefix(ObjectiveType t) {
  switch (t) {
    case ObjectiveType::kSurvey: return "field";
    case ObjectiveType::kThermalSearch: return "search-area";
    case ObjectiveType::kImagePoint: return "mast";
    case ObjectiveType::kDelivery: return "drop-point";
    default: return "home";
  }
}

int agent_turn_budget(const MissionKnobs& k) {
  // Pre-flight, the way home and the landing take three agent turns; each event that makes the
  // supervisor speak early (a peer coming close, a link degradation) takes a dialogue turn pair.
  return k.turns / 2 - 3 - k.traffic - k.degradations;
}

bool is_area(ObjectiveType t) { return t == ObjectiveType::kSurvey || t == ObjectiveType::kThermalSearch; }

// The way around no-fly zones to an area is a turn of its own (route, then lawnmower); to a
// point the route ends at the point. Zones sit across the first leg, so it counts when the
// first objective is an area, which happens only when every objective is one.
int detour_turns(const MissionKnobs& k, const std::vector<ObjectiveType>& kinds) {
  return k.no_fly_zones > 0 && std::all_of(kinds.begin(), kinds.end(), is_area) ? 1 : 0;
}

std::vector<ObjectiveType> draw_kinds(const MissionKnobs& k, Rng& rng) {
  const std::vector<std::pair<ObjectiveType, int>> given = {{ObjectiveType::kSurvey, k.surveys},
                                                            {ObjectiveType::kImagePoint, k.image_points},
                                                            {ObjectiveType::kDelivery, k.deliveries},
                                                            {ObjectiveType::kThermalSearch, k.thermal_searches}};
  std::vector<ObjectiveType> kinds, candidates;
  int steps = 0;
  for (const auto& [type, count] : given) {
    for (int i = 0; i < count; ++i) kinds.push_back(type);
    steps += std::max(count, 0) * objective_steps(type);
    if (count < 0 && (type != ObjectiveType::kDelivery || k.payload_kg > 0.0)) candidates.push_back(type);
  }
  if (k.deliveries > 0 && !(k.payload_kg > 0.0)) throw common::InputError("gen knobs: a delivery needs payload > 0 kg");
  const int budget = agent_turn_budget(k);
  while (static_cast<int>(kinds.size()) < k.objectives) {
    std::vector<ObjectiveType> fitting;
    const int still_to_draw = k.objectives - static_cast<int>(kinds.size()) - 1;  // at least a turn each
    for (auto t : candidates) {
      std::vector<ObjectiveType> with = kinds;
      with.push_back(t);
      const int detour = still_to_draw == 0 ? detour_turns(k, with) : 0;
      if (steps + objective_steps(t) + still_to_draw + detour <= budget) fitting.push_back(t);
    }
    if (fitting.empty()) break;
    kinds.push_back(pick(rng, fitting));
    steps += objective_steps(kinds.back());
  }
  if (steps + detour_turns(k, kinds) > budget || static_cast<int>(kinds.size()) < k.objectives) {
    throw common::InputError("gen knobs: " + std::to_string(k.objectives) + " objectives do not fit turns=" +
                             std::to_string(k.turns) + " (" + std::to_string(budget) +
                             " agent turns for objectives; an image point takes 2, other kinds 1, the way around "
                             "no-fly zones to an area 1)");
  }
  for (std::size_t i = kinds.size(); i > 1; --i) std::swap(kinds[i - 1], kinds[static_cast<std::size_t>(rng.uniform01() * i)]);
  if (k.no_fly_zones > 0) std::stable_partition(kinds.begin(), kinds.end(), [](ObjectiveType t) { return !is_area(t); });
  return kinds;
}

double fence_clearance(const Layout& l, const Vec& p) {
  return common::polygon_contains(l.geofence, p) ? common::polygon_edge_distance(l.geofence, p) : -1.0;
}

// Distance from p to an objective's geometry (0 inside an area).
double distance_to(const DrawnObjective& o, const Vec& p) {
  if (o.area.empty()) return (o.point - p).norm();
  return common::polygon_contains(o.area, p) ? 0.0 : common::polygon_edge_distance(o.area, p);
}

common::Polygon2d rectangle(const Vec& centre, double w, double h) {
  const Vec lo = round_xy(centre - Vec(w / 2, h / 2)), hi = round_xy(centre + Vec(w / 2, h / 2));
  return {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
}

void shape_objective(DrawnObjective& o, const Vec& c, const Layout& l, Rng& rng) {
  o.altitude_m = l.cruise_altitude_m;
  switch (o.type) {
    case ObjectiveType::kSurvey: {
      o.area = rectangle(c, 20 * std::round(rng.uniform(100, 200) / 20), 20 * std::round(rng.uniform(80, 160) / 20));
      o.radius_m = 15.0;
      break;
    }
    case ObjectiveType::kThermalSearch: {
      const double side = 20 * std::round(rng.uniform(120, 180) / 20);
      o.area = rectangle(c, side, side);
      o.target = round_xy(o.area[0] + Vec(rng.uniform(20, side - 20), rng.uniform(20, side - 20)));
      o.radius_m = 25.0;
      o.altitude_m = std::min(l.cruise_altitude_m, 50.0);
      o.sensor = "thermal";
      break;
    }
    case ObjectiveType::kImagePoint:
      o.point = round_xy(c);
      o.sensor = rng.bernoulli(0.3) ? "thermal" : "rgb";
      break;
    default:
      o.point = round_xy(c);
      o.radius_m = 6.0;
      o.drop_altitude_m = 8.0;
      o.sensor = "";
  }
}

bool objective_fits(const DrawnObjective& o, const Layout& l) {
  std::vector<Vec> pts = o.area.empty() ? std::vector<Vec>{o.point} : o.area;
  for (const auto& p : pts) {
    if (fence_clearance(l, p) < kFenceMargin_m || (p - l.home).norm() < 150.0 || (p - l.home).norm() > 900.0) return false;
  }
  for (const auto& other : l.objectives) {
    for (const auto& p : pts) {
      if (distance_to(other, p) < kObjectiveGap_m) return false;
    }
    const std::vector<Vec> theirs = other.area.empty() ? std::vector<Vec>{other.point} : other.area;
    for (const auto& p : theirs) {
      if (distance_to(o, p) < kObjectiveGap_m) return false;
    }
  }
  return true;
}

Vec centre_of(const DrawnObjective& o) { return o.area.empty() ? o.point : 0.5 * (o.area[0] + o.area[2]); }
Vec anchor_of(const DrawnObjective& o) { return o.area.empty() ? o.point : o.area.front(); }

// The first objective sits further out when zones must fit across the way to it.
bool place_objectives(Layout& l, const std::vector<ObjectiveType>& kinds, int zones, Rng& rng) {
  Vec from = l.home;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    DrawnObjective o;
    o.type = kinds[i];
    o.id = kind_prefix(o.type) + "-" + std::to_string(i + 1);
    bool placed = false;
    for (int t = 0; t < kPlacementTries && !placed; ++t) {
      const double nearest_m = i == 0 ? 250.0 + 100.0 * std::min(zones, 3) : 250.0;
      const double a = rng.uniform(0, 2 * M_PI), d = rng.uniform(nearest_m, std::max(600.0, nearest_m + 100.0));
      shape_objective(o, from + d * Vec(std::cos(a), std::sin(a)), l, rng);
      placed = objective_fits(o, l);
    }
    if (!placed) return false;
    if (o.type == ObjectiveType::kSurvey) {
      const auto n = vehicle::survey_waypoints(o.area, reference_spacing_m({}), o.altitude_m, from, 200).waypoints.size();
      o.images_required = std::max(2, static_cast<int>(n) - 2);
    }
    from = centre_of(o);
    l.objectives.push_back(o);
  }
  return true;
}

struct Leg {
  Vec a, b;
};

// Zone k sits across the first leg (k even) or the way home (k odd).
Leg route_leg(const Layout& l, int k) {
  if (k % 2 == 0) return {l.home, anchor_of(l.objectives.front())};
  return {centre_of(l.objectives.back()), l.home};
}

bool zone_fits(const Layout& l, const Vec& c, double extent, const Leg& leg) {
  if ((leg.b - leg.a).norm() < 2 * extent + 150.0) return false;
  if ((c - l.home).norm() < extent + kZoneMargin_m || fence_clearance(l, c) < extent + kZoneFenceGap_m) return false;
  for (const auto& o : l.objectives) {
    if (distance_to(o, c) < extent + kZoneMargin_m) return false;
  }
  for (const auto& z : l.zones) {
    const Vec zc(z["center"][0].get<double>(), z["center"][1].get<double>());
    if ((zc - c).norm() < extent + z["extent_m"].get<double>() + 40.0) return false;
  }
  return true;
}

nlohmann::json zone_json(int k, const Vec& c, bool cylinder, double size, const Vec& along) {
  nlohmann::json z = {{"id", "nfz-" + std::to_string(k + 1)}, {"floor_m", 0}, {"ceiling_m", 300}, {"center", {c.x(), c.y()}}};
  if (cylinder) {
    z.update({{"type", "cylinder"}, {"radius_m", size}, {"extent_m", size}});
    return z;
  }
  const Vec across(-along.y(), along.x());
  nlohmann::json pts = nlohmann::json::array();
  for (const Vec& s : {Vec(-1, -1), Vec(1, -1), Vec(1, 1), Vec(-1, 1)}) {
    const Vec p = round_xy(c + size * (s.x() * along + s.y() * across));
    pts.push_back({p.x(), p.y()});
  }
  z.update({{"type", "polygon"}, {"points", pts}, {"extent_m", size * std::sqrt(2.0)}});
  return z;
}

bool place_zones(Layout& l, int count, Rng& rng) {
  for (int k = 0; k < count; ++k) {
    const Leg leg = route_leg(l, k);
    const Vec along = (leg.b - leg.a).normalized();
    bool placed = false;
    for (int t = 0; t < kPlacementTries && !placed; ++t) {
      const bool cylinder = rng.bernoulli(0.5);
      const double size = std::round(cylinder ? rng.uniform(35, 70) : rng.uniform(30, 50));
      const double extent = cylinder ? size : size * std::sqrt(2.0);
      const double f = k < 2 ? rng.uniform(0.35, 0.5) : rng.uniform(0.55, 0.7);
      const Vec c = round_xy(leg.a + f * (leg.b - leg.a) + rng.uniform(-0.3, 0.3) * size * Vec(-along.y(), along.x()));
      if (!zone_fits(l, c, extent, leg)) continue;
      l.zones.push_back(zone_json(k, c, cylinder, size, along));
      placed = true;
    }
    if (!placed) return false;
  }
  return true;
}

// A patrol back and forth across route leg k at cruise altitude, through its middle.
nlohmann::json patrol_json(const Layout& l, int k) {
  const Leg leg = route_leg(l, k);
  const Vec mid = leg.a + 0.55 * (leg.b - leg.a);
  const Vec across = Vec(-(leg.b - leg.a).y(), (leg.b - leg.a).x()).normalized();
  double half = 250.0;
  while (half > 50.0 && (fence_clearance(l, mid + half * across) < 30.0 || fence_clearance(l, mid - half * across) < 30.0)) {
    half -= 10.0;
  }
  const Vec ends[2] = {round_xy(mid + half * across), round_xy(mid - half * across)};
  nlohmann::json path = nlohmann::json::array();
  auto at = [&](double t, int end) {
    path.push_back({{"t_s", t}, {"p", {ends[end].x(), ends[end].y(), l.cruise_altitude_m}}});
  };
  at(0, 0);
  at(20, 0);
  const double leg_s = std::round(2 * half / 5.0);  // 5 m/s
  int end = 1;
  for (double t = 20 + leg_s; t <= kTrafficHorizon_s; t += leg_s, end = 1 - end) at(t, end);
  return {{"id", "patrol-" + std::to_string(k + 1)}, {"min_separation_m", 30}, {"yields_when_asked", true},
          {"yield_climb_m", 40}, {"conflict_deadline_s", 0}, {"path", path}};
}

nlohmann::json env_json(const MissionKnobs& k, const Layout& l, Rng& rng) {
  bool night = false;
  for (const auto& o : l.objectives) night |= o.type == ObjectiveType::kThermalSearch;
  const std::string weather = night ? "night_clear" : pick(rng, std::vector<std::string>{"clear", "overcast"});
  const double from_deg = std::fmod(5 * std::round(rng.uniform(0, 360) / 5), 360.0);
  return {{"weather", weather}, {"wind_mps", k.wind_mps}, {"wind_dir_deg", from_deg}, {"gust_mps", k.gust_mps}};
}

nlohmann::json payloads_json(const MissionKnobs& k, const Layout& l) {
  bool delivery = false;
  for (const auto& o : l.objectives) delivery |= o.type == ObjectiveType::kDelivery;
  if (!(k.payload_kg > 0.0)) return nlohmann::json::array();
  if (delivery) {
    return {{{"id", "parcel"}, {"type", "parcel_winch"}, {"category", "delivery"}, {"mass_kg", k.payload_kg},
             {"power_W", 15}, {"drag_cdA", 0.02}}};
  }
  return {{{"id", "sensor-pod"}, {"type", "sensor_pod"}, {"category", "sensing"}, {"mass_kg", k.payload_kg},
           {"power_W", 10}, {"drag_cdA", 0.01}}};
}

nlohmann::json network_json(const MissionKnobs& k, Rng& rng) {
  const std::string slice = k.slice != "any" ? k.slice : pick(rng, linkemu::slice_names());
  nlohmann::json windows = nlohmann::json::array();
  for (int i = 0; i < k.degradations; ++i) {
    windows.push_back({{"start_s", std::round(40 + 150 * i + rng.uniform(0, 60))}, {"duration_s", std::round(rng.uniform(40, 90))}});
  }
  nlohmann::json out = {{"initial_slice", slice}};
  if (!windows.empty()) out["degradations"] = windows;
  return out;
}

void draw_frame(Layout& l, const std::string& airframe, Rng& rng) {
  const double w = 50 * std::round(rng.uniform(1000, 1600) / 50), h = 50 * std::round(rng.uniform(800, 1200) / 50);
  l.geofence = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  l.home = round_xy(Vec(rng.uniform(kFenceMargin_m, w - kFenceMargin_m), rng.uniform(kFenceMargin_m, h - kFenceMargin_m)));
  l.home_yaw_deg = 5 * std::round(rng.uniform(0, 355) / 5);
  l.max_altitude_m = pick(rng, std::vector<double>{120.0, 150.0});
  l.cruise_altitude_m = pick(rng, std::vector<double>{40.0, 50.0, 60.0, 70.0});
  l.airframe = airframe;
}

Rng stream(const GeneratorSpec& spec, const char* part, int attempt) {
  return common::RngStreams(spec.seed).stream(std::string("scenario_generator/") + part + "/" + std::to_string(attempt));
}

}  // namespace

int objective_steps(ObjectiveType type) { return type == ObjectiveType::kImagePoint ? 2 : 1; }

std::optional<Layout> draw_layout(const GeneratorSpec& spec, const std::string& airframe, int attempt,
                                  std::string* problem) {
  const MissionKnobs& k = spec.knobs;
  Rng kinds_rng = stream(spec, "kinds", 0), frame_rng = stream(spec, "frame", attempt);
  Rng objectives_rng = stream(spec, "objectives", attempt), zones_rng = stream(spec, "zones", attempt);
  Rng weather_rng = stream(spec, "weather", 0), network_rng = stream(spec, "network", 0);
  Layout l;
  draw_frame(l, airframe, frame_rng);
  if (!place_objectives(l, draw_kinds(k, kinds_rng), k.no_fly_zones, objectives_rng)) {
    *problem = "no room for the objectives in the geofence";
    return std::nullopt;
  }
  if (!place_zones(l, k.no_fly_zones, zones_rng)) {
    *problem = "no room for " + std::to_string(k.no_fly_zones) + " no-fly zones across the route";
    return std::nullopt;
  }
  for (auto& z : l.zones) {
    z.erase("extent_m");
    if (z["type"] == "polygon") z.erase("center");
  }
  for (int i = 0; i < k.traffic; ++i) l.traffic.push_back(patrol_json(l, i));
  l.env = env_json(k, l, weather_rng);
  l.payloads = payloads_json(k, l);
  l.network = network_json(k, network_rng);
  return l;
}

}  // namespace a3::rigs
