// gnuplot figures of the leaderboard.
#include "eval/leaderboard_plots.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.hpp"
#include "common/gnuplot.hpp"
#include "common/png_output.hpp"
#include "eval/leaderboard_format.hpp"

namespace a3::eval {
namespace fs = std::filesystem;
namespace {

std::string script(const fs::path& dir) {
  const std::string data = common::gnuplot_string((dir / "leaderboard.tsv").string());
  // Drawn into "<name><tmp_suffix>" when gnuplot is given tmp_suffix (write_leaderboard_plots).
  auto out = [&](const char* name) { return common::gnuplot_string((dir / name).string()) + ".tmp_suffix"; };
  std::ostringstream gp;
  gp << "# a3rig leaderboard figures; data columns: see the header of leaderboard.tsv\n"
     << "if (!exists('tmp_suffix')) tmp_suffix = ''\n"
     << "set terminal pngcairo size 1100,650 font ',11' noenhanced\n"
     << "set datafile separator '\\t'\n"
     << "set key off\nset grid ytics\nset style fill solid 0.8 border -1\n"
     << "set xtics rotate by -30 left\nset bmargin 9\nset yrange [0:*]\n"
     << "set boxwidth 0.6\n"
     // 1: mean α³ with ci95
     << "set output " << out("mean_score.png") << "\n"
     << "set title 'Mean α³ per model (error bar: 95 % interval)'\nset ylabel 'mean α³'\n"
     << "set yrange [0:1.05]\n"
     << "plot " << data << " using 0:3:xtic(1) with boxes lc rgb '#4C72B0', '' using 0:3:4 "
     << "with yerrorbars lc rgb 'black' lw 1.5 pt 7 ps 0.4\n"
     // 2: α³_rel
     << "set output " << out("alpha3_rel.png") << "\n"
     << "set title 'Reliability-adjusted α³_rel per model'\nset ylabel 'α³_rel'\n"
     << "plot " << data << " using 0:5:xtic(1) with boxes lc rgb '#55A868'\n"
     // 3, 4: efficiency against score
     << "unset xtics\nset xtics rotate by 0\nset bmargin 4\nset autoscale\nset grid xtics ytics\n"
     << "set xlabel 'mean α³'\n"
     << "set output " << out("alpha3_per_1k_tokens_vs_mean.png") << "\n"
     << "set title 'α³ per 1k tokens against mean α³'\nset ylabel 'α³_rel per 1k tokens'\n"
     << "plot " << data << " using 3:6 with points pt 7 ps 1.6 lc rgb '#C44E52', '' using "
     << "3:6:1 with labels offset 1,0.8 left\n"
     << "set output " << out("alpha3_per_second_vs_mean.png") << "\n"
     << "set title 'α³ per second against mean α³'\nset ylabel 'α³_rel per second of generation'\n"
     << "plot " << data << " using 3:7 with points pt 7 ps 1.6 lc rgb '#8172B2', '' using "
     << "3:7:1 with labels offset 1,0.8 left\n"
     // 5: generation time and tokens
     << "unset xlabel\nset xtics rotate by -30 left\nset bmargin 9\nset grid ytics\nunset grid\n"
     << "set terminal pngcairo size 1100,900 font ',11' noenhanced\n"
     << "set output " << out("gen_time_and_tokens.png") << "\n"
     << "set multiplot layout 2,1 title 'Generation cost per model'\n"
     << "set yrange [0:*]\nset title 'mean generation time'\nset ylabel 's'\n"
     << "plot " << data << " using 0:8:xtic(1) with boxes lc rgb '#DD8452'\n"
     << "set title 'mean total tokens'\nset ylabel 'tokens'\n"
     << "plot " << data << " using 0:9:xtic(1) with boxes lc rgb '#937860'\n"
     << "unset multiplot\n";
  return gp.str();
}

std::string leaderboard_tsv(const std::vector<ModelSummary>& rows) {
  std::ostringstream data;
  data << "# model\tdomain\tmean\tci95\talpha3_rel\talpha3_per_1k_tokens\talpha3_per_second"
          "\tmean_gen_time_s\tmean_total_tokens\n";
  for (const auto& r : rows) {
    data << common::gnuplot_data_label(r.model) << "\t" << r.domain << "\t" << format_double(r.mean) << "\t"
         << format_double(r.ci95) << "\t" << format_double(r.alpha3_rel) << "\t"
         << format_double(r.alpha3_per_1k_tokens) << "\t" << format_double(r.alpha3_per_second)
         << "\t" << format_double(r.mean_gen_time_s) << "\t"
         << format_double(r.mean_total_tokens) << "\n";
  }
  return data.str();
}

}  // namespace

const std::vector<std::string>& leaderboard_plot_files() {
  static const std::vector<std::string> kFiles = {
      "mean_score.png", "alpha3_rel.png", "alpha3_per_1k_tokens_vs_mean.png",
      "alpha3_per_second_vs_mean.png", "gen_time_and_tokens.png"};
  return kFiles;
}

void write_leaderboard_plots(const fs::path& dir, const std::vector<ModelSummary>& rows) {
  if (rows.empty()) throw std::runtime_error("no model to plot");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create: " + ec.message());
  const fs::path abs_dir = fs::absolute(dir);
  common::write_file_atomically(abs_dir / "leaderboard.tsv", leaderboard_tsv(rows));
  const fs::path script_path = abs_dir / "plots.gp";
  common::write_file_atomically(script_path, script(abs_dir));
  try {
    common::run_gnuplot(script_path, abs_dir / "gnuplot.log",
                        {"tmp_suffix=" + common::gnuplot_string(common::temporary_png_suffix())});
    for (const auto& name : leaderboard_plot_files()) common::commit_png(common::temporary_png_path(abs_dir / name), abs_dir / name);
  } catch (...) {
    for (const auto& name : leaderboard_plot_files()) std::filesystem::remove(common::temporary_png_path(abs_dir / name), ec);
    throw;
  }
}

}  // namespace a3::eval
