// The two batch scripts of a sweep on Slurm (`a3rig sweep --slurm`), as text: a job array whose
// task I runs shard I/N of the sweep (`a3rig sweep <the user's flags> --shard I/N`), and a merge
// job, submitted to start after every task has ended (afterany), that merges the shards' results
// files, aggregates and plots, and fails naming the shards that left no results file. Pure
// functions: nothing is written or submitted here (rigs/sweep/slurm_submit.hpp does that).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace a3::rigs::sweep {

struct SlurmJobOptions {
  std::filesystem::path a3rig_exe;      // absolute: the compute nodes run this program
  std::vector<std::string> sweep_args;  // the sweep's flags as given, minus the Slurm ones and --shard
  std::filesystem::path work_dir;       // absolute: the jobs start here, so relative flags mean the same
  std::filesystem::path out_dir;        // absolute: the sweep's --out, on a filesystem the nodes share
  std::filesystem::path shared_dir;     // exported as A3_SHARED_DIR; empty: not exported
  int shards = 1;                       // array tasks 0 .. shards-1
  int array_parallelism = 0;            // at most this many tasks at once (%K); 0: no limit
  int cpus_per_task = 1;
  std::string partition;                // empty: the cluster's default partition
  std::string time_limit;               // per task, as sbatch --time takes it; empty: the partition's
  std::vector<std::string> sbatch_args; // extra sbatch options, one #SBATCH line each
};

// OUT/slurm: the scripts, and logs/ with one file per task and one for the merge.
std::filesystem::path slurm_dir(const std::filesystem::path& out_dir);
std::filesystem::path array_script_path(const std::filesystem::path& out_dir);
std::filesystem::path merge_script_path(const std::filesystem::path& out_dir);

// The job array: `#SBATCH --array=0-(N-1)[%K]`; each task runs shard ${SLURM_ARRAY_TASK_ID}/N
// (N written in, so a task resubmitted alone with `sbatch --array=I` keeps its numbering).
std::string array_script(const SlurmJobOptions& options);
// The merge: `a3rig sweep --plot-only OUT --expect-shards N`.
std::string merge_script(const SlurmJobOptions& options);

// A word for a POSIX shell: unchanged when it holds only safe characters, else in single quotes.
std::string shell_quote(const std::string& word);
// Words as one command line to paste into a POSIX shell: each shell_quote'd, space-separated.
std::string shell_command(const std::vector<std::string>& words);
// A value on an #SBATCH line (sbatch's own parser, not a shell): in double quotes with
// backslash before \ " and #, when it holds anything but safe characters.
std::string sbatch_quote(const std::string& value);
// A path in sbatch --output, whose % starts a pattern (%A, %a, %j): % doubled.
std::string sbatch_filename_literal(const std::string& path);

}  // namespace a3::rigs::sweep
