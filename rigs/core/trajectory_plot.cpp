// The trajectory plot: its data (trajectory.tsv) and script (trajectory.gp) written whole, and
// trajectory.png drawn by gnuplot into a temporary file that is renamed only when gnuplot
// succeeded and the PNG is complete (gnuplot exits 0 even when a full disk cut the PNG short).
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/png_output.hpp"
#include "common/polygon.hpp"
#include "rigs/core/episode_writer.hpp"

namespace a3::rigs {
namespace {

namespace fs = std::filesystem;

std::string trajectory_tsv(const RecordedEpisode& rec) {
  std::ostringstream d;
  d << "# t_s\tx_m\ty_m\tz_m\tbattery_pct\tspeed_mps\n";
  for (const auto& p : rec.trajectory) d << p[0] << "\t" << p[1] << "\t" << p[2] << "\t" << p[3] << "\t" << p[4] << "\t" << p[5] << "\n";
  return d.str();
}

struct MapFrame {
  double x0 = 1e18, x1 = -1e18, y0 = 1e18, y1 = -1e18;
  void extend(double x, double y, double r) {
    x0 = std::min(x0, x - r);
    x1 = std::max(x1, x + r);
    y0 = std::min(y0, y - r);
    y1 = std::max(y1, y + r);
  }
};

// The map frames the track, the objectives and the no-fly zones (not the whole geofence).
MapFrame map_frame(const Scenario& s, const RecordedEpisode& rec) {
  MapFrame f;
  for (const auto& p : rec.trajectory) f.extend(p[1], p[2], 0.0);
  for (const auto& o : s.mission.objectives) {
    for (const auto& p : o.area) f.extend(p.x(), p.y(), 0.0);
    if (o.type == agent::ObjectiveType::kImagePoint || o.type == agent::ObjectiveType::kDelivery) f.extend(o.point.x(), o.point.y(), o.radius_m);
  }
  for (const auto& z : s.airspace.no_fly_zones) {
    if (z.polygon.empty()) f.extend(z.centre.x(), z.centre.y(), z.radius_m);
    for (const auto& p : z.polygon) f.extend(p.x(), p.y(), 0.0);
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

void airspace_objects(std::ostream& gp, const Scenario& s) {
  int obj = 1;
  if (s.airspace.geofence.size() >= 3) polygon_object(gp, obj++, s.airspace.geofence, "fs empty border lc rgb '#888888' dt 2");
  for (const auto& z : s.airspace.no_fly_zones) {
    if (z.polygon.empty()) {
      gp << "set object " << obj++ << " circle at " << z.centre.x() << "," << z.centre.y() << " size " << z.radius_m
         << " fs transparent solid 0.25 fc rgb '#d62728'\n";
    }
  }
  for (const auto& o : s.mission.objectives) {
    if (o.area.size() >= 3) {
      polygon_object(gp, obj++, o.area, "fs transparent solid 0.15 fc rgb '#2ca02c'");
    } else if (o.type != agent::ObjectiveType::kReturnAndLand) {
      gp << "set label " << obj++ << " '" << o.id << "' at " << o.point.x() << "," << o.point.y() << " point pt 7 ps 1.5 lc rgb '#2ca02c' offset 1,1\n";
    }
  }
}

// The script draws into trajectory.png, or into png_out when given (gnuplot -e "png_out='...'").
std::string trajectory_script(const fs::path& abs, const Scenario& s, const RecordedEpisode& rec) {
  const MapFrame f = map_frame(s, rec);
  const double pad = 0.08 * std::max(f.x1 - f.x0, f.y1 - f.y0) + 10.0;
  const std::string tsv = (abs / "trajectory.tsv").string();
  std::ostringstream gp;
  gp << "if (!exists('png_out')) png_out = '" << (abs / "trajectory.png").string() << "'\n"
     << "set terminal pngcairo size 1200,550 font ',10' noenhanced\nset output png_out\n"
     << "set multiplot layout 1,2 title '" << s.name << "'\n"
     << "set size ratio -1\nset xlabel 'east (m)'\nset ylabel 'north (m)'\nset grid\nset key bottom right\n"
     << "set xrange [" << f.x0 - pad << ":" << f.x1 + pad << "]\nset yrange [" << f.y0 - pad << ":" << f.y1 + pad << "]\n";
  airspace_objects(gp, s);
  gp << "plot '" << tsv << "' using 2:3 with lines lw 2 lc rgb '#1f77b4' title 'ground track'\n"
     << "unset object\nunset label\nset size noratio\nset autoscale\nset xlabel 'mission time (s)'\nset ylabel 'altitude (m)'\n"
     << "set y2label 'battery (%)'\nset y2tics\nset ytics nomirror\n"
     << "plot '" << tsv << "' using 1:4 with lines lw 2 title 'altitude', '' using 1:5 axes x1y2 with lines lw 2 title 'battery'\n"
     << "unset multiplot\nunset output\n";
  return gp.str();
}

}  // namespace

std::string write_trajectory_plot(const fs::path& dir, const Scenario& s, const RecordedEpisode& rec) {
  if (rec.trajectory.empty()) return "no trajectory recorded";
  const fs::path abs = fs::absolute(dir);
  common::write_file_atomically(abs / "trajectory.tsv", trajectory_tsv(rec));
  common::write_file_atomically(abs / "trajectory.gp", trajectory_script(abs, s, rec));
  const fs::path png = abs / "trajectory.png";
  const fs::path temporary = common::temporary_png_path(png);
  const fs::path log = abs / "gnuplot.log";
  const std::string cmd = "gnuplot -e \"png_out='" + temporary.string() + "'\" '" + (abs / "trajectory.gp").string() +
                          "' > '" + log.string() + "' 2>&1";
  const int exit_status = std::system(cmd.c_str());
  if (exit_status != 0) {
    ::unlink(temporary.c_str());
    return "gnuplot failed with status " + std::to_string(exit_status) + " (see " + log.string() + ")";
  }
  common::commit_png(temporary, png);
  std::error_code ec;
  if (fs::file_size(log, ec) == 0 && !ec) fs::remove(log, ec);  // gnuplot had nothing to say
  return "";
}

}  // namespace a3::rigs
