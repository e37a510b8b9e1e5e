// The sbatch calls of `a3rig sweep --slurm`.
#include "rigs/sweep/slurm_submit.hpp"

#include <stdexcept>

#include "common/atomic_file.hpp"

namespace a3::rigs::sweep {
namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::string submit(const std::vector<std::string>& argv, CommandRunner& runner) {
  const std::string line = shell_command(argv);
  const CapturedOutput result = runner.run(argv);
  if (result.exit_status != 0) {
    const std::string why = trimmed(result.err).empty() ? trimmed(result.out) : trimmed(result.err);
    throw std::runtime_error("`" + line + "` failed (exit status " + std::to_string(result.exit_status) +
                             "): " + (why.empty() ? "no message" : why));
  }
  return parse_job_id(result.out);
}

void make_executable(const std::filesystem::path& path) {
  using std::filesystem::perms;
  std::filesystem::permissions(path, perms::owner_exec | perms::group_exec | perms::others_exec,
                               std::filesystem::perm_options::add);
}

}  // namespace

void write_slurm_scripts(const SlurmJobOptions& options) {
  const std::string array = array_script(options);
  const std::string merge = merge_script(options);
  std::filesystem::create_directories(slurm_dir(options.out_dir) / "logs");
  common::write_file_atomically(array_script_path(options.out_dir), array);
  common::write_file_atomically(merge_script_path(options.out_dir), merge);
  make_executable(array_script_path(options.out_dir));
  make_executable(merge_script_path(options.out_dir));
}

std::string parse_job_id(const std::string& parsable_output) {
  const std::string text = trimmed(parsable_output);
  const std::string id = text.substr(0, text.find(';'));
  const bool digits = !id.empty() && id.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) throw std::runtime_error("sbatch --parsable printed '" + text + "', not a job id");
  return id;
}

SlurmSubmission submit_slurm_jobs(const std::filesystem::path& out_dir, CommandRunner& runner) {
  SlurmSubmission submission;
  submission.array_job_id = submit({"sbatch", "--parsable", array_script_path(out_dir).string()}, runner);
  const std::vector<std::string> merge = {"sbatch", "--parsable", "--dependency=afterany:" + submission.array_job_id,
                                          merge_script_path(out_dir).string()};
  try {
    submission.merge_job_id = submit(merge, runner);
  } catch (const std::exception& e) {
    const std::string by_hand = shell_command(merge);
    throw std::runtime_error("job array " + submission.array_job_id + " is submitted, the merge job is not: " +
                             e.what() + "; submit it by hand: " + by_hand);
  }
  return submission;
}

}  // namespace a3::rigs::sweep
