// Writing the sweep's Slurm scripts into OUT/slurm/ and submitting them with sbatch: the job
// array first, then the merge job with --dependency=afterany:<array job> — afterany, not
// afterok, so that the merge runs (and names the shards that left no results) even when a task
// failed or hit its time limit; with afterok it would wait forever for a dependency never met.
#pragma once

#include <filesystem>
#include <string>

#include "rigs/sweep/captured_command.hpp"
#include "rigs/sweep/slurm_job.hpp"

namespace a3::rigs::sweep {

struct SlurmSubmission {
  std::string array_job_id;
  std::string merge_job_id;
};

// Writes OUT/slurm/array.sbatch and merge.sbatch (executable) and creates OUT/slurm/logs/ (Slurm
// does not create the folder of --output: a task without it fails with no log at all).
void write_slurm_scripts(const SlurmJobOptions& options);

// The job id of `sbatch --parsable` output: "123" or "123;cluster" (a trailing newline allowed).
// Throws std::runtime_error quoting the output when it is not one.
std::string parse_job_id(const std::string& parsable_output);

// Submits the scripts written by write_slurm_scripts. Throws std::runtime_error with sbatch's
// stderr when a submission fails; when the merge job fails after the array was submitted, the
// message gives the array's id and the command to submit the merge by hand.
SlurmSubmission submit_slurm_jobs(const std::filesystem::path& out_dir, CommandRunner& runner);

}  // namespace a3::rigs::sweep
