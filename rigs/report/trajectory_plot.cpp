// The trajectory plot: its data (trajectory.tsv) and script (trajectory.gp) written whole, and
// trajectory.png drawn by gnuplot into a temporary file that is renamed only when gnuplot
// succeeded and the PNG is complete (gnuplot exits 0 even when a full disk cut the PNG short).
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/gnuplot.hpp"
#include "common/png_output.hpp"
#include "common/polygon.hpp"
#include "rigs/outputs/episode_writer.hpp"
#include "rigs/report/trajectory_plot.hpp"

namespace a3::rigs {
namespace {

namespace fs = std::filesystem;

std::string trajectory_tsv(const RecordedEpisode& rec) {
  std::ostringstream d;
  d << "# t_s\tx_m\ty_m\tz_m\tbattery_pct\tspeed_mps\n";
  for (const auto& p : rec.trajectory) d << p[0] << "\t" << p[1] << "\t" << p[2] << "\t" << p[3] << "\t" << p[4] << "\t" << p[5] << "\n";
  return d.str();
}

std::string quoted(const std::string& text) { return common::gnuplot_string(text); }

std::string number_text(double value) {
  std::ostringstream t;
  t << value;
  return t.str();
}

std::string metres(double value_m) { return number_text(value_m) + " m"; }

struct MapFrame {
  double x0 = 1e18, x1 = -1e18, y0 = 1e18, y1 = -1e18;
  void extend(double x, double y, double r) {
    x0 = std::min(x0, x - r);
    x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r);
    y1 = std::max(y1, y + r);
  }
};

// The map frames the track, the geofence, the objectives, home, the zones and the peers' plans.
MapFrame map_frame(const Scenario& s, const RecordedEpisode& rec) {
  MapFrame f;
  for (const auto& p : rec.trajectory) f.extend(p[1], p[2], 0.0);
  for (const auto& p : s.airspace.geofence) f.extend(p.x(), p.y(), 0.0);
  f.extend(s.mission.home_W_m.x(), s.mission.home_W_m.y(), 0.0);
  for (const auto& o : s.mission.objectives) {
    for (const auto& p : o.area) f.extend(p.x(), p.y(), 0.0);
    if (o.type == agent::ObjectiveType::kImagePoint || o.type == agent::ObjectiveType::kDelivery) f.extend(o.point.x(), o.point.y(), o.radius_m);
  }
  for (const auto& z : s.airspace.no_fly_zones) {
    if (z.polygon.empty()) f.extend(z.centre.x(), z.centre.y(), z.radius_m);
    for (const auto& p : z.polygon) f.extend(p.x(), p.y(), 0.0);
  }
  for (const auto& t : s.airspace.traffic) {
    for (const auto& w : t.path) f.extend(w.p_W_m.x(), w.p_W_m.y(), 0.0);
  }
  return f;
}

void polygon_object(std::ostream& gp, int id, const common::Polygon2d& points, const char* style) {
  gp << "set object " << id << " polygon from ";
  for (std::size_t i = 0; i <= points.size(); ++i) {
    const auto& p = points[i % points.size()];
    gp << (i ? " to " : "") << p.x() << "," << p.y();
  }
  gp << " " << style << "\n";
}

Eigen::Vector2d vertex_mean(const common::Polygon2d& points) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// "hospital 0 m to 500 m" (ground / no ceiling when unbounded).
std::string zone_label(const agent::NoFlyZone& z) {
  const std::string floor = std::isfinite(z.floor_m) ? metres(z.floor_m) : "ground";
  const std::string ceiling = std::isfinite(z.ceiling_m) ? metres(z.ceiling_m) : "no ceiling";
  return z.id + " " + floor + " to " + ceiling;
}

constexpr const char* kZoneStyle = "fs transparent solid 0.25 fc rgb '#d62728' lw 1";
constexpr const char* kAreaStyle = "fs transparent solid 0.15 fc rgb '#2ca02c'";

void zone_objects(std::ostream& gp, const Scenario& s, int& object, int& label) {
  for (const auto& z : s.airspace.no_fly_zones) {
    Eigen::Vector2d at = z.centre;
    if (z.polygon.size() >= 3) {
      polygon_object(gp, object++, z.polygon, kZoneStyle);
      at = vertex_mean(z.polygon);
    } else {
      gp << "set object " << object++ << " circle at " << z.centre.x() << "," << z.centre.y() << " size " << z.radius_m
         << " " << kZoneStyle << "\n";
    }
    gp << "set label " << label++ << " " << quoted(zone_label(z)) << " at " << at.x() << "," << at.y()
       << " center tc rgb '#8b0000'\n";
  }
}

void objective_objects(std::ostream& gp, const Scenario& s, int& object, int& label) {
  for (const auto& o : s.mission.objectives) {
    if (o.area.size() >= 3) {
      polygon_object(gp, object++, o.area, kAreaStyle);
      const Eigen::Vector2d at = vertex_mean(o.area);
      gp << "set label " << label++ << " " << quoted(o.id) << " at " << at.x() << "," << at.y() << " center tc rgb '#1a6b1a'\n";
    } else if (o.type != agent::ObjectiveType::kReturnAndLand) {
      gp << "set label " << label++ << " " << quoted(o.id) << " at " << o.point.x() << "," << o.point.y()
         << " point pt 7 ps 1.5 lc rgb '#2ca02c' offset 1,1\n";
    }
  }
  gp << "set label " << label++ << " 'home' at " << s.mission.home_W_m.x() << "," << s.mission.home_W_m.y()
     << " point pt 5 ps 1.5 lc rgb '#000000' offset 1,-1\n";
}

void world_objects(std::ostream& gp, const Scenario& s) {
  int object = 1, label = 1;
  if (s.airspace.geofence.size() >= 3) polygon_object(gp, object++, s.airspace.geofence, "fs empty border lc rgb '#555555' dt 2 lw 1.5");
  zone_objects(gp, s, object, label);
  objective_objects(gp, s, object, label);
}

// "t=20, 220 s at 60 m": the times of every waypoint at path[i]'s position, on the first of
// them only (a patrol passes the same points again and again); "" on the others.
std::string waypoint_label(const std::vector<agent::TrafficWaypoint>& path, std::size_t i) {
  constexpr double kSamePlace_m = 1.0;
  std::string times;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if ((path[k].p_W_m - path[i].p_W_m).norm() > kSamePlace_m) continue;
    if (k < i) return "";
    times += (times.empty() ? "" : ", ") + number_text(path[k].t_s);
  }
  return "t=" + times + " s at " + metres(path[i].p_W_m.z());
}

// One data block per peer: x, y and the waypoint's label, one row per waypoint.
void peer_blocks(std::ostream& gp, const Scenario& s) {
  for (std::size_t i = 0; i < s.airspace.traffic.size(); ++i) {
    const auto& path = s.airspace.traffic[i].path;
    gp << "$peer_" << i << " << EOD\n";
    for (std::size_t k = 0; k < path.size(); ++k) {
      gp << path[k].p_W_m.x() << " " << path[k].p_W_m.y() << " " << common::gnuplot_data_label(waypoint_label(path, k)) << "\n";
    }
    gp << "EOD\n";
  }
}

struct EventStyle {
  const char* kind;
  const char* style;
};

// Known kinds first, in this order; any other kind is drawn grey.
constexpr EventStyle kEventStyles[] = {
    {"nfz_intrusion", "pt 2 ps 2 lw 2 lc rgb '#d62728'"},       {"separation_breach", "pt 9 ps 2 lc rgb '#ff7f0e'"},
    {"crash", "pt 7 ps 2.5 lc rgb '#000000'"},                   {"gate_refusal", "pt 4 ps 1.8 lw 2 lc rgb '#9467bd'"},
    {"failsafe", "pt 13 ps 2 lc rgb '#e377c2'"},                 {"altitude_violation", "pt 11 ps 2 lc rgb '#8c564b'"}};
constexpr const char* kOtherEventStyle = "pt 6 ps 1.5 lc rgb '#7f7f7f'";

const char* event_style(const std::string& kind) {
  for (const auto& e : kEventStyles) {
    if (kind == e.kind) return e.style;
  }
  return kOtherEventStyle;
}

std::map<std::string, std::vector<const a3lcm::safety_event_t*>> events_by_kind(const RecordedEpisode& rec) {
  std::map<std::string, std::vector<const a3lcm::safety_event_t*>> by_kind;
  for (const auto& e : rec.safety) by_kind[e.kind].push_back(&e);
  return by_kind;
}

std::string block_name(const std::string& kind) {
  std::string name = "$events_";
  for (char c : kind) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
}

// One data block per event kind: x, y, one row per event.
void event_blocks(std::ostream& gp, const RecordedEpisode& rec) {
  for (const auto& [kind, events] : events_by_kind(rec)) {
    gp << block_name(kind) << " << EOD\n";
    for (const auto* e : events) gp << e->p_W_m[0] << " " << e->p_W_m[1] << "\n";
    gp << "EOD\n";
  }
}

// The map's plot elements: legend entries for the drawn objects, the track, peers and events.
std::string map_plot(const std::string& tsv, const Scenario& s, const RecordedEpisode& rec) {
  std::vector<std::string> items;
  if (s.airspace.geofence.size() >= 3) items.push_back("keyentry with lines lc rgb '#555555' dt 2 lw 1.5 title 'geofence'");
  if (!s.airspace.no_fly_zones.empty()) items.push_back("keyentry with boxes " + std::string(kZoneStyle) + " title 'no-fly zone'");
  items.push_back(quoted(tsv) + " using 2:3 with lines lw 2 lc rgb '#1f77b4' title 'ground track'");
  static constexpr const char* kPeerColours[] = {"#17becf", "#bcbd22", "#7f7f7f", "#e377c2"};
  for (std::size_t i = 0; i < s.airspace.traffic.size(); ++i) {
    const std::string block = "$peer_" + std::to_string(i);
    items.push_back(block + " using 1:2 with linespoints dt 3 lw 1.5 pt 1 lc rgb '" + kPeerColours[i % 4] + "' title " +
                    quoted("peer " + s.airspace.traffic[i].id + " (plan)"));
    items.push_back(block + " using 1:2:3 with labels offset 0,1 font ',8' tc rgb '" + kPeerColours[i % 4] + "' notitle");
  }
  for (const auto& [kind, events] : events_by_kind(rec)) {
    items.push_back(block_name(kind) + " using 1:2 with points " + event_style(kind) + " title " +
                    quoted(kind + " (" + std::to_string(events.size()) + ")"));
  }
  std::string plot = "plot ";
  for (std::size_t i = 0; i < items.size(); ++i) plot += (i ? ", \\\n     " : "") + items[i];
  return plot + "\n";
}

}  // namespace

std::string trajectory_plot_script(const fs::path& dir, const Scenario& s, const RecordedEpisode& rec) {
  const fs::path abs = fs::absolute(dir);
  const MapFrame f = map_frame(s, rec);
  const double pad = 0.05 * std::max(f.x1 - f.x0, f.y1 - f.y0) + 10.0;
  const std::string tsv = (abs / "trajectory.tsv").string();
  std::ostringstream gp;
  gp << "if (!exists('png_out')) png_out = " << quoted((abs / "trajectory.png").string()) << "\n"
     << "set terminal pngcairo size 1400,650 font ',10' noenhanced\nset output png_out\n";
  peer_blocks(gp, s);
  event_blocks(gp, rec);
  gp << "set multiplot layout 1,2 title " << quoted(s.name) << "\n"
     << "set size ratio -1\nset xlabel 'east (m)'\nset ylabel 'north (m)'\nset grid\n"
     << "set key outside bottom center horizontal box opaque font ',9'\n"
     << "set xrange [" << f.x0 - pad << ":" << f.x1 + pad << "]\nset yrange [" << f.y0 - pad << ":" << f.y1 + pad << "]\n";
  world_objects(gp, s);
  gp << map_plot(tsv, s, rec)
     << "unset object\nunset label\nset size noratio\nset autoscale\nset key default\nset key bottom right\n"
     << "set xlabel 'mission time (s)'\nset ylabel 'altitude (m)'\n"
     << "set y2label 'battery (%)'\nset y2tics\nset ytics nomirror\n"
     << "plot " << quoted(tsv) << " using 1:4 with lines lw 2 title 'altitude', '' using 1:5 axes x1y2 with lines lw 2 title 'battery'\n"
     << "unset multiplot\nunset output\n";
  return gp.str();
}

std::string write_trajectory_plot(const fs::path& dir, const Scenario& s, const RecordedEpisode& rec) {
  if (rec.trajectory.empty()) return "no trajectory recorded";
  const fs::path abs = fs::absolute(dir);
  common::write_file_atomically(abs / "trajectory.tsv", trajectory_tsv(rec));
  common::write_file_atomically(abs / "trajectory.gp", trajectory_plot_script(abs, s, rec));
  const fs::path png = abs / "trajectory.png";
  const fs::path temporary = common::temporary_png_path(png);
  const fs::path log = abs / "gnuplot.log";
  try {
    common::run_gnuplot(abs / "trajectory.gp", log, {"png_out=" + quoted(temporary.string())});
  } catch (const std::runtime_error&) {
    ::unlink(temporary.c_str());
    return "gnuplot failed (see " + log.string() + ")";
  }
  common::commit_png(temporary, png);
  std::error_code ec;
  if (fs::file_size(log, ec) == 0 && !ec) fs::remove(log, ec);  // gnuplot had nothing to say
  return "";
}

}  // namespace a3::rigs
