// Drawing the latency-sensitivity plots with gnuplot: data and scripts written whole, each PNG
// drawn into a temporary name and renamed when complete.
#include "rigs/sweep/sweep_plot.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/gnuplot.hpp"
#include "common/png_output.hpp"
#include "rigs/sweep/sweep_grid.hpp"

namespace a3::rigs::sweep {
namespace {

const char* slice_colour(const std::string& slice) {
  if (slice == "eMBB") return "#1f77b4";
  if (slice == "URLLC") return "#2ca02c";
  if (slice == "mMTC") return "#d62728";
  return "#7f7f7f";
}

int slice_order(const std::string& slice) {
  if (slice == "eMBB") return 0;
  if (slice == "URLLC") return 1;
  if (slice == "mMTC") return 2;
  return 3;
}

std::string quoted(const std::filesystem::path& p) { return common::gnuplot_string(p.string()); }

std::string number_text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

std::string plot_data(std::vector<const AggregateRow*> rows) {
  std::sort(rows.begin(), rows.end(), [](const AggregateRow* a, const AggregateRow* b) {
    return a->think_time_mean_s < b->think_time_mean_s;
  });
  std::ostringstream out;
  out << "# think_time_mean_s alpha3 lo hi SP lo hi success_rate lo hi n think_time\n";
  auto band = [](double mean, const std::optional<Interval>& ci) {
    return ci ? std::make_pair(ci->lo, ci->hi) : std::make_pair(mean, mean);
  };
  for (const AggregateRow* a : rows) {
    const auto [a_lo, a_hi] = band(a->alpha3_mean, a->alpha3_ci);
    const auto [s_lo, s_hi] = band(a->sp_mean, a->sp_ci);
    const auto [r_lo, r_hi] = band(a->success_rate, a->success_ci);
    out << a->think_time_mean_s << " " << a->alpha3_mean << " " << a_lo << " " << a_hi << " " << a->sp_mean << " "
        << s_lo << " " << s_hi << " " << a->success_rate << " " << r_lo << " " << r_hi << " " << a->n << " "
        << common::gnuplot_data_label(a->think_time) << "\n";
  }
  return out.str();
}

using Figure = std::pair<std::string, std::string>;  // scenario, agent
using SliceRows = std::map<std::string, std::vector<const AggregateRow*>>;

void add_problem(PlotOutcome& outcome, const std::string& problem) {
  outcome.problem += (outcome.problem.empty() ? "" : "; ") + problem;
}

// One figure's data files, script and PNG; throws common::OutputError when a file cannot be written.
void draw_figure(const std::filesystem::path& dir, const Figure& figure, const SliceRows& slices, PlotOutcome& outcome) {
  const std::string stem = "sweep_" + folder_name(figure.first) + "_" + folder_name(figure.second);
  std::vector<std::pair<std::string, std::filesystem::path>> data;  // slice, data file
  int n_min = 1 << 30, n_max = 0;
  for (const auto& [slice, group] : slices) {
    const auto path = dir / (stem + "_" + folder_name(slice) + ".dat");
    common::write_file_atomically(path, plot_data(group));
    data.emplace_back(slice, path);
    for (const AggregateRow* a : group) {
      n_min = std::min(n_min, a->n);
      n_max = std::max(n_max, a->n);
    }
  }
  std::sort(data.begin(), data.end(), [](const auto& a, const auto& b) { return slice_order(a.first) < slice_order(b.first); });
  // Slices that coincide (the same SP on two slices, say) would hide each other: their points
  // are dodged sideways by ±0.8 % of the axis, said in the plot's title.
  double x_max_s = 0.0;
  for (const auto& [slice, group] : slices) {
    for (const AggregateRow* a : group) x_max_s = std::max(x_max_s, a->think_time_mean_s);
  }
  const double dodge_s = 0.008 * std::max(x_max_s, 1.0);
  const auto png = dir / (stem + ".png");
  const auto script = dir / (stem + ".gp");
  {
    std::ostringstream gp;
    const std::string n_text = n_min == n_max ? std::to_string(n_min) : std::to_string(n_min) + "–" + std::to_string(n_max);
    gp << "if (!exists('png_out')) png_out = " << quoted(png) << "\n"
       << "set terminal pngcairo size 1650,520 font ',11' noenhanced\n"
       << "set output png_out\n"
       << "set multiplot layout 1,3 title "
       << common::gnuplot_string(figure.first + " — agent " + figure.second + " — n = " + n_text +
                                 " episodes per point; bands: 95 % CI (Student t for α³ and SP, Wilson for the "
                                 "success rate); slices dodged ±" + number_text(dodge_s) + " s")
       << "\n"
       << "set xlabel 'think time per agent turn, mean (s)'\n"
       << "set xrange [" << -3.0 * dodge_s << ":" << std::max(x_max_s, 1.0) + 3.0 * dodge_s << "]\n"
       << "set yrange [-0.03:1.03]\nset grid\nset key below horizontal\n"
       << "set style fill transparent solid 0.15 noborder\n";
    const std::pair<const char*, int> panels[] = {{"α³", 2}, {"SP (safety)", 5}, {"success rate", 8}};
    for (const auto& [title, column] : panels) {
      gp << "set title '" << title << "'\nset ylabel '" << title << "'\nplot ";
      bool first = true;
      for (const auto& [slice, path] : data) {
        const std::string colour = slice_colour(slice);
        const int order = slice_order(slice);
        const std::string x = "($1+(" + std::to_string((std::min(order, 2) - 1) * dodge_s) + "))";
        const int point_type[] = {7, 5, 9, 13};
        gp << (first ? "" : ", \\\n     ") << quoted(path) << " using " << x << ":" << column + 1 << ":"
           << column + 2 << " with filledcurves lc rgb '" << colour << "' notitle, \\\n     " << quoted(path)
           << " using " << x << ":" << column << " with linespoints lw 2 pt " << point_type[order]
           << " ps 0.9 dt " << order + 1 << " lc rgb '" << colour << "' title " << common::gnuplot_string(slice);
        first = false;
      }
      gp << "\n";
    }
    gp << "unset multiplot\nunset output\n";
    common::write_file_atomically(script, gp.str());
  }
  const auto log = dir / (stem + ".gnuplot.log");
  std::filesystem::remove(png);  // a PNG left from an earlier run must not pass for this one
  const auto temporary = common::temporary_png_path(png);
  try {
    common::run_gnuplot(script, log, {"png_out=" + quoted(temporary)});
  } catch (const std::runtime_error&) {
    ::unlink(temporary.c_str());
    add_problem(outcome, "gnuplot failed on " + script.string() + " (see " + log.string() + ")");
    return;
  }
  common::commit_png(temporary, png);
  outcome.pngs.push_back(png);
}

}  // namespace

PlotOutcome write_sweep_plots(const std::filesystem::path& plots_dir, const std::vector<AggregateRow>& rows) {
  PlotOutcome outcome;
  const auto dir = std::filesystem::absolute(plots_dir);
  std::filesystem::create_directories(dir);
  // (scenario, agent) → slice → the aggregate rows with episodes.
  std::map<Figure, SliceRows> figures;
  for (const auto& a : rows) {
    if (a.n > 0) figures[{a.scenario, a.agent}][a.slice].push_back(&a);
  }
  if (!common::gnuplot_found()) {
    outcome.problem = "gnuplot not found (Debian package gnuplot-nox); aggregate.csv holds the numbers";
    return outcome;
  }
  for (const auto& [figure, slices] : figures) {
    try {
      draw_figure(dir, figure, slices, outcome);
    } catch (const common::OutputError& e) {
      add_problem(outcome, e.what());
    }
  }
  return outcome;
}

}  // namespace a3::rigs::sweep
