// Progress bar and ETA of a sweep.
#include "rigs/sweep/progress.hpp"

#include <cmath>

namespace a3::rigs::sweep {

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const long total = std::lround(seconds);
  char buffer[32];
  if (total >= 3600) {
    std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", total / 3600, (total % 3600) / 60);
  } else if (total >= 60) {
    std::snprintf(buffer, sizeof buffer, "%ldm%02lds", total / 60, total % 60);
  } else {
    std::snprintf(buffer, sizeof buffer, "%lds", total);
  }
  return buffer;
}

std::string progress_line(const ProgressCounts& c, int bar_width) {
  const std::size_t done = c.ran + c.skipped + c.failed;
  const double fraction = c.total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(c.total);
  const int filled = static_cast<int>(std::floor(fraction * bar_width));
  std::string line = "[" + std::string(filled, '#') + std::string(bar_width - filled, '-') + "]";
  const std::size_t run = c.ran + c.failed;
  const double rate = run > 0 && c.elapsed_s > 0.0 ? static_cast<double>(run) / c.elapsed_s : 0.0;
  const std::size_t run_remaining = c.to_run > run ? c.to_run - run : 0;
  char buffer[200];
  std::snprintf(buffer, sizeof buffer, " %zu/%zu %3d%%  ran %zu  skipped %zu  failed %zu", done, c.total,
                static_cast<int>(std::floor(fraction * 100.0)), c.ran, c.skipped, c.failed);
  line += buffer;
  if (rate > 0.0) {
    std::snprintf(buffer, sizeof buffer, "  %.2f episodes/s", rate);
    line += buffer;
  }
  if (done == c.total) {
    line += "  done in " + format_duration(c.elapsed_s);
  } else if (run_remaining == 0) {
    line += "  ETA 0s";
  } else {
    line += "  ETA " + (rate > 0.0 ? format_duration(static_cast<double>(run_remaining) / rate) : std::string("?"));
  }
  return line;
}

ProgressBar::ProgressBar(std::FILE* out, bool redraw_in_place, double line_period_s)
    : out_(out), redraw_in_place_(redraw_in_place), line_period_s_(line_period_s) {}

void ProgressBar::update(const ProgressCounts& counts) {
  if (redraw_in_place_) {
    std::fprintf(out_, "\r%s\033[K", progress_line(counts).c_str());
    std::fflush(out_);
    return;
  }
  if (counts.elapsed_s - last_line_s_ < line_period_s_) return;
  last_line_s_ = counts.elapsed_s;
  std::fprintf(out_, "%s\n", progress_line(counts).c_str());
  std::fflush(out_);
}

void ProgressBar::finish(const ProgressCounts& counts) {
  std::fprintf(out_, redraw_in_place_ ? "\r%s\033[K\n" : "%s\n", progress_line(counts).c_str());
  std::fflush(out_);
}

}  // namespace a3::rigs::sweep
