// The sweep's progress on stderr: a bar redrawn in place on a terminal, plain lines (at most
// one every few seconds, and the last) otherwise, with the rate of episodes run and the ETA.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

namespace a3::rigs::sweep {

struct ProgressCounts {
  std::size_t total = 0;    // cells of this shard
  std::size_t to_run = 0;   // of which incomplete when the sweep started (the ETA's work)
  std::size_t ran = 0;      // episodes run to completion
  std::size_t skipped = 0;  // complete already (resumed)
  std::size_t failed = 0;   // run, without a complete episode
  double elapsed_s = 0.0;
};

// "1h02m", "3m07s", "12s".
std::string format_duration(double seconds);
// "[#####---------------]  25/100  25%  ran 20  skipped 5  failed 0  1.3 episodes/s  ETA 57s";
// the ETA counts only the cells still to run (to_run - ran - failed), at the rate of those run so far.
std::string progress_line(const ProgressCounts& counts, int bar_width = 24);

class ProgressBar {
 public:
  ProgressBar(std::FILE* out, bool redraw_in_place, double line_period_s = 5.0);
  void update(const ProgressCounts& counts);
  void finish(const ProgressCounts& counts);

 private:
  std::FILE* out_;
  bool redraw_in_place_;
  double line_period_s_;
  double last_line_s_ = -1e9;
};

}  // namespace a3::rigs::sweep
