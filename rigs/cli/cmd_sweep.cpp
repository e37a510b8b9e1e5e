// `a3rig sweep`: a grid of episodes (scenarios × agents × think times × slices × seeds), each
// run as its own `a3rig run`, in parallel, resumable and shardable, with results.csv,
// aggregate.csv and latency-sensitivity plots; `--plot-only DIR` re-aggregates (and merges
// shards) from the results files alone; `--slurm` submits it as a Slurm job array and a merge job.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/scenario/builtin_scenarios.hpp"
#include "rigs/scenario/scenario.hpp"
#include "rigs/scenario/shared_dir.hpp"
#include "rigs/sweep/cell_result.hpp"
#include "rigs/sweep/cell_runner.hpp"
#include "rigs/sweep/slurm_job.hpp"
#include "rigs/sweep/slurm_submit.hpp"
#include "rigs/sweep/sweep_estimate.hpp"
#include "rigs/sweep/sweep_report.hpp"
#include "rigs/sweep/sweep_runner.hpp"

namespace a3::rigs {
namespace {

struct SweepArgs {
  std::string scenarios;
  std::string agents = "scripted";
  std::string think_times = "0,5,10,20,30,60,120";
  std::string slices = "eMBB,URLLC,mMTC";
  std::string seeds = "1-5";
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::string runtime = "virtual";
  double real_time_factor = 1.0;
  std::string shard = "0/1";
  std::string out = "out/sweep";
  double cell_timeout_s = -1.0;  // negative: 900 s in virtual time, none in real time
  bool rerun = false;
  int realtime_retries = 2;
  bool dry_run = false;
  std::string plot_only;
  std::string llm_base_url;
  std::string llm_model;
  int expect_shards = 0;
  // Slurm
  bool slurm = false;
  bool slurm_dry_run = false;
  std::string partition;
  std::string time_limit;
  int array_parallelism = 0;
  int slurm_shards = 0;  // 0: min(cells, 64)
  int cpus_per_task = 0;  // 0: --jobs when given, else 1
  std::vector<std::string> sbatch_args;
};

// The flags only a Slurm submission takes; they are not passed on to the array's tasks.
const std::vector<std::string>& slurm_flags() {
  static const std::vector<std::string> names = {"--slurm", "--slurm-dry-run", "--partition", "--time",
                                                 "--array-parallelism", "--slurm-shards", "--cpus-per-task",
                                                 "--sbatch-arg"};
  return names;
}

bool given(const CLI::App& cmd, const std::string& name) { return cmd.get_option(name)->count() > 0; }

// Flag combinations that cannot mean what the user wants, named.
void check_flag_combinations(const SweepArgs& args, const CLI::App& cmd) {
  const bool slurm = args.slurm || args.slurm_dry_run;
  if (given(cmd, "--expect-shards") && args.plot_only.empty()) {
    throw std::invalid_argument("--expect-shards goes with --plot-only DIR");
  }
  if (!slurm) {
    for (const auto& name : slurm_flags()) {
      if (given(cmd, name)) throw std::invalid_argument(name + " goes with --slurm (or --slurm-dry-run)");
    }
    return;
  }
  for (const std::string name : {"--shard", "--dry-run", "--plot-only"}) {
    if (given(cmd, name)) {
      throw std::invalid_argument(name + " cannot go with --slurm" +
                                  (name == "--shard" ? ": the job array gives each task its shard" :
                                   name == "--dry-run" ? ": --slurm-dry-run prints the scripts" : ""));
    }
  }
}

// The flags the user gave, in the order of the help, minus the Slurm ones: the array tasks'
// command line. --jobs and --out are added when not given, so every task uses its cpus and
// the folder the scripts are in.
std::vector<std::string> task_args(const SweepArgs& args, const CLI::App& cmd, int cpus_per_task) {
  std::vector<std::string> words;
  for (const CLI::Option* opt : cmd.get_options()) {
    const std::string name = opt->get_name();
    if (opt->count() == 0 || name == "--help" ||
        std::find(slurm_flags().begin(), slurm_flags().end(), name) != slurm_flags().end()) {
      continue;
    }
    if (opt->get_expected_max() == 0) {
      words.push_back(name);
      continue;
    }
    for (const auto& value : opt->results()) words.insert(words.end(), {name, value});
  }
  if (!given(cmd, "--jobs")) words.insert(words.end(), {"--jobs", std::to_string(cpus_per_task)});
  if (!given(cmd, "--out")) words.insert(words.end(), {"--out", args.out});
  return words;
}

std::string all_builtin_scenarios() {
  std::string names;
  for (const auto& [name, text] : builtin_scenarios()) names += (names.empty() ? "" : ",") + std::string(name);
  return names;
}

void print_report(const sweep::SweepReport& report) {
  std::printf("aggregate: %s (%zu groups; 95 %% CI: Student t for α³ and SP, Wilson for the success rate)\n",
              report.aggregate_path.c_str(), report.aggregates.size());
  for (const auto& png : report.plots.pngs) std::printf("plot:      %s\n", png.c_str());
  if (!report.plots.problem.empty()) std::printf("plots:     not all drawn: %s\n", report.plots.problem.c_str());
  std::printf("index:     %s (plots, aggregate and every cell linked to its report)\n", report.index_path.c_str());
}

// --expect-shards N: the shards without a results file, named with the way to run them again.
bool report_missing_shards(const std::filesystem::path& dir, int expect_shards) {
  const std::vector<int> missing = sweep::missing_shards(dir, expect_shards);
  if (missing.empty()) return false;
  std::string list;
  for (const int i : missing) list += (list.empty() ? "" : ",") + std::to_string(i);
  std::printf("missing:   %zu of %d shards left no results file: %s; run them again (on Slurm: sbatch --array=%s "
              "%s, then the merge job again; see docs/slurm.md)\n",
              missing.size(), expect_shards, list.c_str(), list.c_str(),
              sweep::shell_quote(sweep::array_script_path(dir).string()).c_str());
  return true;
}

int plot_only(const std::filesystem::path& dir, int expect_shards) {
  const bool shards_missing = expect_shards > 0 && report_missing_shards(dir, expect_shards);
  if (shards_missing && sweep::result_files(dir).empty()) return 1;
  const sweep::MergedReport merged = sweep::reaggregate(dir);
  for (const auto& f : merged.merged_files) std::printf("read:      %s\n", f.c_str());
  std::printf("results:   %s (%zu cells)\n", (dir / "results.csv").c_str(), merged.rows);
  print_report(merged.report);
  if (expect_shards == 0) return 0;
  const auto rows = sweep::read_results_csv(dir / "results.csv");
  const auto incomplete = std::count_if(rows.begin(), rows.end(), [](const auto& r) { return !r.has_episode; });
  if (incomplete > 0) std::printf("failed:    %td cells without a complete episode (their status in results.csv)\n", incomplete);
  return shards_missing || incomplete > 0 ? 1 : 0;
}

void print_slurm_dry_run(const sweep::SlurmJobOptions& job) {
  std::printf("# %s\n%s\n# %s\n%s\n", sweep::array_script_path(job.out_dir).c_str(), sweep::array_script(job).c_str(),
              sweep::merge_script_path(job.out_dir).c_str(), sweep::merge_script(job).c_str());
  std::printf("# submitted with: sbatch --parsable %s, then sbatch --parsable --dependency=afterany:<array job id> %s\n",
              sweep::shell_quote(sweep::array_script_path(job.out_dir).string()).c_str(),
              sweep::shell_quote(sweep::merge_script_path(job.out_dir).string()).c_str());
}

int submit_to_slurm(const sweep::SlurmJobOptions& job) {
  sweep::write_slurm_scripts(job);
  sweep::ProcessCommandRunner sbatch;
  sweep::SlurmSubmission ids;
  try {
    ids = sweep::submit_slurm_jobs(job.out_dir, sbatch);
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "a3rig sweep --slurm: %s\n", e.what());
    return 1;
  }
  const std::string both = ids.array_job_id + "," + ids.merge_job_id;
  std::printf("slurm:     array job %s (%d shards), merge job %s (runs after every task has ended)\n",
              ids.array_job_id.c_str(), job.shards, ids.merge_job_id.c_str());
  std::printf("scripts:   %s, %s\n", sweep::array_script_path(job.out_dir).c_str(),
              sweep::merge_script_path(job.out_dir).c_str());
  std::printf("logs:      %s/\n", (sweep::slurm_dir(job.out_dir) / "logs").c_str());
  std::printf("follow:    squeue -j %s; sacct -j %s; results in %s/results.csv when job %s has ended\n", both.c_str(),
              both.c_str(), job.out_dir.c_str(), ids.merge_job_id.c_str());
  return 0;
}

int run_on_slurm(const SweepArgs& args, const CLI::App& cmd, std::size_t cells, const std::string& a3rig_exe) {
  sweep::SlurmJobOptions job;
  job.shards = args.slurm_shards > 0 ? args.slurm_shards : static_cast<int>(std::min<std::size_t>(cells, 64));
  if (static_cast<std::size_t>(job.shards) > cells) {
    throw std::invalid_argument("--slurm-shards " + std::to_string(job.shards) + ": more shards than the sweep's " +
                                std::to_string(cells) + " cells");
  }
  job.cpus_per_task = args.cpus_per_task > 0 ? args.cpus_per_task : (given(cmd, "--jobs") ? args.jobs : 1);
  job.a3rig_exe = a3rig_exe;
  job.sweep_args = task_args(args, cmd, job.cpus_per_task);
  job.work_dir = std::filesystem::current_path();
  job.out_dir = std::filesystem::absolute(args.out).lexically_normal();
  if (const auto shared = default_shared_dir(); std::filesystem::exists(shared)) {
    job.shared_dir = std::filesystem::absolute(shared).lexically_normal();
  }
  job.array_parallelism = args.array_parallelism;
  job.partition = args.partition;
  job.time_limit = args.time_limit;
  job.sbatch_args = args.sbatch_args;
  if (args.slurm_dry_run) {
    print_slurm_dry_run(job);
    return 0;
  }
  return submit_to_slurm(job);
}

std::string this_program() {
  char exe[4096];
  const ssize_t length = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (length <= 0) throw std::runtime_error("cannot find the a3rig program (/proc/self/exe)");
  return std::string(exe, static_cast<std::size_t>(length));
}

// Each scenario's mission time limit (for the estimate); a scenario that does not load is a bad
// --scenarios item.
std::map<std::string, double> time_limits_of(const std::vector<std::string>& scenarios) {
  const std::filesystem::path shared_dir = default_shared_dir();
  std::map<std::string, double> time_limit_s;
  for (const auto& scenario : scenarios) {
    try {
      time_limit_s[scenario] = load_scenario_spec(scenario, shared_dir).mission.time_limit_s;
    } catch (const std::exception& e) {
      throw std::invalid_argument("--scenarios: '" + scenario + "': " + e.what());
    }
  }
  return time_limit_s;
}

sweep::ChildProcessOptions child_options(const SweepArgs& args) {
  sweep::ChildProcessOptions child;
  child.a3rig_exe = this_program();
  child.runtime = args.runtime;
  child.real_time_factor = args.real_time_factor;
  child.cell_timeout_s = args.cell_timeout_s >= 0.0 ? args.cell_timeout_s : (args.runtime == "virtual" ? 900.0 : 0.0);
  if (!args.llm_base_url.empty()) child.extra_run_args.insert(child.extra_run_args.end(), {"--llm-base-url", args.llm_base_url});
  if (!args.llm_model.empty()) child.extra_run_args.insert(child.extra_run_args.end(), {"--llm-model", args.llm_model});
  return child;
}

// The closing lines: where the results are, how fast, what failed, and the report (or how to
// gather the shards).
void print_summary(const sweep::SweepRunSummary& summary, const SweepArgs& args, const sweep::Shard& shard) {
  const auto& c = summary.counts;
  std::printf("results:   %s (%zu cells: %zu run, %zu already complete, %zu failed%s)\n", summary.results_path.c_str(),
              c.total, c.ran, c.skipped, c.failed, summary.stopped ? ", the rest not run: stopped" : "");
  if (c.ran + c.failed > 0) {
    std::printf("wall time: %.1f s for %zu episodes run with %d jobs: %.2f episodes/s\n", c.elapsed_s, c.ran + c.failed,
                args.jobs, static_cast<double>(c.ran + c.failed) / std::max(c.elapsed_s, 1e-9));
  }
  if (summary.realtime_reruns > 0) {
    std::printf("real time: %zu run(s) repeated because the host broke the real-time contract (status "
                "realtime_violated; see README \"Real time\")\n", summary.realtime_reruns);
  }
  for (const auto& row : summary.rows) {
    if (!row.has_episode && row.status.rfind("not_run", 0) != 0) {
      const bool interrupted = row.status.rfind("stopped", 0) == 0;
      std::printf("%s %s / %s / think %s / %s / seed %llu: %s\n", interrupted ? "rerun next:" : "failed:   ",
                  row.scenario.c_str(), row.agent.c_str(),
                  row.think_time.c_str(), row.slice.c_str(), static_cast<unsigned long long>(row.seed),
                  row.status.c_str());
    }
  }
  if (shard.count == 1) {
    print_report(sweep::write_report(args.out, summary.rows));
  } else {
    std::printf("shard %d/%d done; once every shard is, gather their folders into one (e.g. cp -r shard-*/. all/) and "
                "run `a3rig sweep --plot-only all` for results.csv, aggregate.csv and the plots\n",
                shard.index, shard.count);
  }
}

int run(const SweepArgs& args, const CLI::App& cmd) {
  check_flag_combinations(args, cmd);
  if (!args.plot_only.empty()) return plot_only(args.plot_only, args.expect_shards);
  const sweep::SweepAxes axes = sweep::make_axes(args.scenarios.empty() ? all_builtin_scenarios() : args.scenarios,
                                                 args.agents, args.think_times, args.slices, args.seeds);
  const sweep::Shard shard = sweep::parse_shard(args.shard);
  const std::map<std::string, double> time_limit_s = time_limits_of(axes.scenarios);
  const std::vector<sweep::SweepCell> grid = sweep::expand_grid(axes);
  if (args.slurm || args.slurm_dry_run) return run_on_slurm(args, cmd, grid.size(), this_program());
  const std::vector<sweep::SweepCell> mine = sweep::cells_of_shard(grid, shard);

  sweep::ChildProcessCellRunner runner(child_options(args));

  std::fprintf(stderr,
               "a3rig sweep: %zu cells (%zu scenarios × %zu agents × %zu think times × %zu slices × %zu seeds); "
               "shard %d/%d: %zu cells; %d jobs; %s time; output %s\n",
               grid.size(), axes.scenarios.size(), axes.agents.size(), axes.think_times.size(), axes.slices.size(),
               axes.seeds.size(), shard.index, shard.count, mine.size(), args.jobs, args.runtime.c_str(),
               args.out.c_str());
  std::vector<bool> done(mine.size(), false);
  std::vector<sweep::SweepCell> to_run;
  for (std::size_t i = 0; i < mine.size(); ++i) {
    done[i] = !args.rerun && sweep::check_cell(sweep::cell_dir(args.out, mine[i]), mine[i]).complete;
    if (!done[i]) to_run.push_back(mine[i]);
  }
  const auto estimate = sweep::estimate_sweep(to_run, args.runtime, args.real_time_factor, args.jobs, time_limit_s);
  std::fprintf(stderr, "a3rig sweep: %zu cells to run (%zu already complete): %s\n", to_run.size(),
               mine.size() - to_run.size(), sweep::estimate_text(estimate, to_run.size(), args.real_time_factor).c_str());
  if (args.dry_run) {
    for (std::size_t i = 0; i < mine.size(); ++i) {
      const std::string line = sweep::shell_command(runner.command(mine[i], sweep::cell_dir(args.out, mine[i])));
      std::printf("%5zu  %s  %s\n", mine[i].index, done[i] ? "done  " : "to run", line.c_str());  // to paste as it is
    }
    return 0;
  }

  std::atomic<bool> stop{false};
  auto watcher = std::make_unique<StopWatcher>(stop);
  sweep::ProgressBar bar(stderr, ::isatty(STDERR_FILENO) == 1);
  sweep::SweepRunOptions options;
  options.out_dir = args.out;
  options.shard = shard;
  options.jobs = args.jobs;
  options.rerun_complete = args.rerun;
  options.realtime_retries = args.realtime_retries;
  sweep::SweepRunSummary summary;
  summary = sweep::run_sweep(grid, options, runner, [&](const sweep::ProgressCounts& c) { bar.update(c); }, stop);
  watcher.reset();
  bar.finish(summary.counts);

  print_summary(summary, args, shard);
  if (summary.stopped || stop) return 3;
  return summary.counts.failed > 0 ? 1 : 0;
}

}  // namespace

A3_REGISTER_COMMAND("15-sweep", [](CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Run a grid of episodes — scenarios × agents × think times × slices × seeds — each as its own `a3rig run` "
      "(virtual time by default), up to --jobs at a time. Every cell gets a folder "
      "OUT/cells/<scenario>/<agent>/think-<t>/<slice>/seed-<s>/ (episode.json, run.log); OUT/results.csv has a row "
      "per episode (keys, status, success, α³, the six pillars, mission and wall time), OUT/aggregate.csv the mean "
      "α³ and SP with Student-t 95 % intervals and the success rate with its Wilson 95 % interval per scenario × "
      "agent × think time × slice, and OUT/plots/sweep_<scenario>_<agent>.png plots them against think time, one "
      "line per slice, with the intervals as bands. Resumable: a cell whose episode.json is complete is not run "
      "again (--rerun to force). Shardable: --shard I/N runs the cells whose grid index % N == I and writes "
      "OUT/results.shard-I-of-N.csv; to merge, gather the shards' folders into one and run --plot-only on it. "
      "Exit status: 0 every cell complete, 1 some cell failed (see its run.log), 2 bad usage, 3 stopped (Ctrl-C).");
  cmd->add_option("--scenarios", args->scenarios,
                  "comma list of scenarios, as `a3rig run --scenario` takes them (default: every built-in one)");
  cmd->add_option("--agents", args->agents, "comma list: scripted, llm, replay:<episode.json> (default scripted)");
  cmd->add_option("--think-times", args->think_times,
                  "comma list of think-time specs as `a3rig run --think-time` takes them: seconds, fixed:S, "
                  "uniform:A,B, normal:M,SD, lognormal:MEDIAN,SIGMA, exp:MEAN, model:<name> (default "
                  "0,5,10,20,30,60,120); plotted at their mean per agent turn");
  cmd->add_option("--slices", args->slices, "comma list of starting slices: eMBB, URLLC, mMTC (default all three)");
  cmd->add_option("--seeds", args->seeds, "comma list of seeds and ranges, e.g. 1,2,3 or 1-5 (default 1-5)");
  cmd->add_option("-j,--jobs", args->jobs, "episodes run at once (default: the number of cores)")
      ->check(a3::rigs::between(1, 1024));
  cmd->add_option("--runtime", args->runtime, "virtual (default: as fast as possible) or real (the wall clock)")
      ->check(CLI::IsMember({"real", "virtual"}));
  cmd->add_option("--rtf", args->real_time_factor, "real time: simulated seconds per wall second (default 1)")
      ->check(a3::rigs::positive());
  cmd->add_option("--shard", args->shard, "I/N: run only the cells whose grid index % N == I (default 0/1: all)");
  cmd->add_option("--out", args->out, "output folder, created when absent (default out/sweep)")->check(a3::rigs::output_folder());
  cmd->add_option("--cell-timeout", args->cell_timeout_s,
                  "wall seconds one episode may take before it is killed and recorded as failed; 0: no limit "
                  "(default 900 in virtual time, none in real time)")
      ->check(a3::rigs::non_negative());
  cmd->add_flag("--rerun", args->rerun, "run every cell again, complete or not");
  cmd->add_option("--realtime-retries", args->realtime_retries,
                  "real time: runs again a cell whose run broke the real-time contract (status realtime_violated: the "
                  "host could not keep the pace) up to this many times, then lists it as failed (default 2)")
      ->check(a3::rigs::between(0, 100));
  cmd->add_flag("--dry-run", args->dry_run, "list the cells of this shard (done or to run) and their commands");
  cmd->add_option("--plot-only", args->plot_only,
                  "DIR: run nothing; merge DIR's results.csv and results.shard-*.csv into DIR/results.csv and write "
                  "aggregate.csv and the plots again");
  cmd->add_option("--llm-base-url", args->llm_base_url, "--agents llm: passed to every `a3rig run`");
  cmd->add_option("--llm-model", args->llm_model, "--agents llm: passed to every `a3rig run`");
  cmd->add_option("--expect-shards", args->expect_shards,
                  "N, with --plot-only: also check that DIR holds the results of every shard I/N and that every "
                  "cell has a complete episode; exit 1 naming the missing shards and counting the failed cells "
                  "(the Slurm merge job runs this)")
      ->check(a3::rigs::between(1, 100000));
  cmd->add_flag("--slurm", args->slurm,
                "submit the sweep to Slurm instead of running it: writes OUT/slurm/array.sbatch (a job array, task I "
                "runs this sweep's flags with --shard I/N) and OUT/slurm/merge.sbatch (--plot-only OUT "
                "--expect-shards N), submits them with sbatch (the merge with --dependency=afterany on the array) "
                "and prints the job ids; OUT, this program and the shared data must be visible from the compute "
                "nodes at the same paths (docs/slurm.md)");
  cmd->add_flag("--slurm-dry-run", args->slurm_dry_run, "print the two Slurm scripts --slurm would submit; write and submit nothing");
  cmd->add_option("--slurm-shards", args->slurm_shards, "Slurm: array tasks N, one shard each (default: the number of cells, at most 64)")
      ->check(a3::rigs::between(1, 1000));
  cmd->add_option("--array-parallelism", args->array_parallelism, "Slurm: at most K array tasks at once (--array=0-(N-1)%K; default no limit)")
      ->check(a3::rigs::between(1, 1000));
  cmd->add_option("--partition", args->partition, "Slurm: the partition of both jobs (default the cluster's)");
  cmd->add_option("--time", args->time_limit, "Slurm: time limit per array task and for the merge, as sbatch --time takes it, e.g. 2:00:00 (default the partition's)");
  cmd->add_option("--cpus-per-task", args->cpus_per_task,
                  "Slurm: cpus per array task; each task runs that many episodes at once (default --jobs when given, else 1)")
      ->check(a3::rigs::between(1, 1024));
  cmd->add_option("--sbatch-arg", args->sbatch_args,
                  "Slurm: one more sbatch option for both jobs, e.g. --sbatch-arg=--account=proj --sbatch-arg=--mem=4G (repeatable)");
  cmd->callback([args, cmd] { command_exit_status() = run(*args, *cmd); });
});

}  // namespace a3::rigs
