// Writing the text of the sweep's Slurm job array and merge job.
#include "rigs/sweep/slurm_job.hpp"

#include <stdexcept>

namespace a3::rigs::sweep {
namespace {

bool is_safe(const std::string& word) {
  if (word.empty()) return false;
  for (const char c : word) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!alnum && std::string_view("_-+=/.,:@%").find(c) == std::string_view::npos) return false;
  }
  return true;
}

void check(const SlurmJobOptions& o) {
  if (!o.a3rig_exe.is_absolute()) throw std::invalid_argument("a3rig program " + o.a3rig_exe.string() + ": not absolute");
  if (!o.work_dir.is_absolute()) throw std::invalid_argument("working folder " + o.work_dir.string() + ": not absolute");
  if (!o.out_dir.is_absolute()) throw std::invalid_argument("--out " + o.out_dir.string() + ": not absolute");
  if (o.shards < 1) throw std::invalid_argument("--slurm-shards " + std::to_string(o.shards) + ": must be at least 1");
  if (o.array_parallelism < 0 || o.cpus_per_task < 1) {
    throw std::invalid_argument("--array-parallelism must be >= 0 and --cpus-per-task >= 1");
  }
}

std::string directive(const std::string& option, const std::string& value) {
  return "#SBATCH " + option + "=" + sbatch_quote(value) + "\n";
}

// The #SBATCH lines both jobs share after their name: cpus, folder, output, partition, time, extras.
std::string common_directives(const SlurmJobOptions& o, int cpus, const std::string& output_pattern) {
  std::string text = directive("--cpus-per-task", std::to_string(cpus));
  text += directive("--chdir", o.work_dir.string());
  text += directive("--output", sbatch_filename_literal((slurm_dir(o.out_dir) / "logs").string()) + "/" + output_pattern);
  if (!o.partition.empty()) text += directive("--partition", o.partition);
  if (!o.time_limit.empty()) text += directive("--time", o.time_limit);
  for (const auto& extra : o.sbatch_args) text += "#SBATCH " + sbatch_quote(extra) + "\n";
  return text;
}

std::string environment(const SlurmJobOptions& o) {
  if (o.shared_dir.empty()) return "";
  return "export A3_SHARED_DIR=" + shell_quote(o.shared_dir.string()) + "\n";
}

std::string command_line(const std::vector<std::string>& words) { return "exec " + shell_command(words); }

}  // namespace

std::filesystem::path slurm_dir(const std::filesystem::path& out_dir) { return out_dir / "slurm"; }
std::filesystem::path array_script_path(const std::filesystem::path& out_dir) { return slurm_dir(out_dir) / "array.sbatch"; }
std::filesystem::path merge_script_path(const std::filesystem::path& out_dir) { return slurm_dir(out_dir) / "merge.sbatch"; }

std::string array_script(const SlurmJobOptions& o) {
  check(o);
  const std::string n = std::to_string(o.shards);
  std::string text = "#!/bin/bash\n# a3rig sweep on Slurm: array task I runs shard I/" + n +
                     " of the sweep (written by `a3rig sweep --slurm`).\n";
  text += directive("--job-name", "a3rig-sweep");
  std::string array = "0-" + std::to_string(o.shards - 1);
  if (o.array_parallelism > 0) array += "%" + std::to_string(o.array_parallelism);
  text += directive("--array", array);
  text += common_directives(o, o.cpus_per_task, "shard_%A_%a.out");
  text += environment(o);
  std::vector<std::string> words = {o.a3rig_exe.string(), "sweep"};
  words.insert(words.end(), o.sweep_args.begin(), o.sweep_args.end());
  words.push_back("--shard");
  return text + command_line(words) + " \"${SLURM_ARRAY_TASK_ID}/" + n + "\"\n";
}

std::string merge_script(const SlurmJobOptions& o) {
  check(o);
  const std::string n = std::to_string(o.shards);
  std::string text = "#!/bin/bash\n# a3rig sweep on Slurm: merges the results of the " + n +
                     " shards, aggregates and plots; fails naming the shards without results (written by "
                     "`a3rig sweep --slurm`, submitted with --dependency=afterany:<array job>).\n";
  text += directive("--job-name", "a3rig-sweep-merge");
  text += common_directives(o, 1, "merge_%j.out");
  text += environment(o);
  return text + command_line({o.a3rig_exe.string(), "sweep", "--plot-only", o.out_dir.string(), "--expect-shards", n}) +
         "\n";
}

std::string shell_quote(const std::string& word) {
  if (is_safe(word)) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_command(const std::vector<std::string>& words) {
  std::string line;
  for (const auto& w : words) line += (line.empty() ? "" : " ") + shell_quote(w);
  return line;
}

std::string sbatch_quote(const std::string& value) {
  if (is_safe(value)) return value;
  if (value.find_first_of("\r\n") != std::string::npos) {
    throw std::invalid_argument("'" + value + "': a line break cannot go on an #SBATCH line");
  }
  std::string quoted = "\"";
  for (const char c : value) {
    if (c == '\\' || c == '"' || c == '#') quoted += '\\';
    quoted += c;
  }
  return quoted + "\"";
}

std::string sbatch_filename_literal(const std::string& path) {
  std::string literal;
  for (const char c : path) literal += c == '%' ? std::string("%%") : std::string(1, c);
  return literal;
}

}  // namespace a3::rigs::sweep
