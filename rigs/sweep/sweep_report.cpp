// Writing aggregate.csv and the plots; merging results files first for --plot-only.
#include "rigs/sweep/sweep_report.hpp"

#include <stdexcept>

#include "rigs/sweep/sweep_index.hpp"

namespace a3::rigs::sweep {

SweepReport write_report(const std::filesystem::path& out_dir, const std::vector<ResultRow>& rows) {
  SweepReport report;
  report.aggregates = aggregate(rows);
  report.aggregate_path = out_dir / "aggregate.csv";
  write_aggregate_csv(report.aggregate_path, report.aggregates);
  report.plots = write_sweep_plots(out_dir / "plots", report.aggregates);
  report.index_path = write_sweep_index(out_dir, rows, report.aggregates, report.plots.pngs);
  return report;
}

MergedReport reaggregate(const std::filesystem::path& out_dir) {
  MergedReport merged;
  merged.merged_files = result_files(out_dir);
  if (merged.merged_files.empty()) {
    throw std::runtime_error(out_dir.string() +
                             ": no results.csv nor results.shard-I-of-N.csv (is this the --out folder of a sweep?)");
  }
  const std::vector<ResultRow> rows = merge_result_files(merged.merged_files);
  write_results_csv(out_dir / "results.csv", rows);
  merged.rows = rows.size();
  merged.report = write_report(out_dir, rows);
  return merged;
}

}  // namespace a3::rigs::sweep
