// The Slurm scripts of `a3rig sweep --slurm` as text (exact, for given options), the quoting of
// paths for the shell and for sbatch's #SBATCH parser, writing the scripts, and the submission
// (the merge job's dependency, sbatch failures) with a fake sbatch.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "rigs/sweep/slurm_job.hpp"
#include "rigs/sweep/slurm_submit.hpp"
#include "rigs/sweep/sweep_runner.hpp"

namespace a3::rigs::sweep {
namespace {

namespace fs = std::filesystem;

SlurmJobOptions example_job() {
  SlurmJobOptions job;
  job.a3rig_exe = "/opt/a3/bin/a3rig";
  job.sweep_args = {"--scenarios", "traffic-conflict", "--think-times", "0,uniform:1,4", "--jobs", "2", "--out", "out/s"};
  job.work_dir = "/home/me/runs";
  job.out_dir = "/home/me/runs/out/s";
  job.shared_dir = "/data/shared";
  job.shards = 12;
  job.array_parallelism = 4;
  job.cpus_per_task = 2;
  job.partition = "short";
  job.time_limit = "1:00:00";
  job.sbatch_args = {"--account=uav"};
  return job;
}

TEST(SweepSlurmScripts, TheArrayRunsShardIOfNWithTheSweepsFlags) {
  EXPECT_EQ(array_script(example_job()),
            "#!/bin/bash\n"
            "# a3rig sweep on Slurm: array task I runs shard I/12 of the sweep (written by `a3rig sweep --slurm`).\n"
            "#SBATCH --job-name=a3rig-sweep\n"
            "#SBATCH --array=0-11%4\n"
            "#SBATCH --cpus-per-task=2\n"
            "#SBATCH --chdir=/home/me/runs\n"
            "#SBATCH --output=/home/me/runs/out/s/slurm/logs/shard_%A_%a.out\n"
            "#SBATCH --partition=short\n"
            "#SBATCH --time=1:00:00\n"
            "#SBATCH --account=uav\n"
            "export A3_SHARED_DIR=/data/shared\n"
            "exec /opt/a3/bin/a3rig sweep --scenarios traffic-conflict --think-times 0,uniform:1,4 --jobs 2 "
            "--out out/s --shard \"${SLURM_ARRAY_TASK_ID}/12\"\n");
}

TEST(SweepSlurmScripts, WithoutOptionalSettingsTheArrayHasNoLimitPartitionTimeNorSharedDir) {
  SlurmJobOptions job = example_job();
  job.array_parallelism = 0;
  job.partition.clear();
  job.time_limit.clear();
  job.sbatch_args.clear();
  job.shared_dir.clear();
  const std::string text = array_script(job);
  EXPECT_NE(text.find("#SBATCH --array=0-11\n"), std::string::npos) << text;
  EXPECT_EQ(text.find("--partition"), std::string::npos);
  EXPECT_EQ(text.find("--time"), std::string::npos);
  EXPECT_EQ(text.find("A3_SHARED_DIR"), std::string::npos);
}

TEST(SweepSlurmScripts, TheMergeExpectsEveryShardAndRunsOnOneCpu) {
  EXPECT_EQ(merge_script(example_job()),
            "#!/bin/bash\n"
            "# a3rig sweep on Slurm: merges the results of the 12 shards, aggregates and plots; fails naming the "
            "shards without results (written by `a3rig sweep --slurm`, submitted with "
            "--dependency=afterany:<array job>).\n"
            "#SBATCH --job-name=a3rig-sweep-merge\n"
            "#SBATCH --cpus-per-task=1\n"
            "#SBATCH --chdir=/home/me/runs\n"
            "#SBATCH --output=/home/me/runs/out/s/slurm/logs/merge_%j.out\n"
            "#SBATCH --partition=short\n"
            "#SBATCH --time=1:00:00\n"
            "#SBATCH --account=uav\n"
            "export A3_SHARED_DIR=/data/shared\n"
            "exec /opt/a3/bin/a3rig sweep --plot-only /home/me/runs/out/s --expect-shards 12\n");
}

TEST(SweepSlurmScripts, PathsWithSpacesQuotesAndPercentAreQuotedForSbatchAndTheShell) {
  SlurmJobOptions job = example_job();
  job.work_dir = "/home/me/my \"runs\"";
  job.out_dir = "/home/me/it's 100% #1";
  job.sweep_args = {"--out", "/home/me/it's 100% #1"};
  const std::string text = array_script(job);
  EXPECT_NE(text.find("#SBATCH --chdir=\"/home/me/my \\\"runs\\\"\"\n"), std::string::npos) << text;
  EXPECT_NE(text.find("#SBATCH --output=\"/home/me/it's 100%% \\#1/slurm/logs/shard_%A_%a.out\"\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find(" --out '/home/me/it'\\''s 100% #1' --shard"), std::string::npos) << text;
}

TEST(SweepSlurmScripts, ShellQuotingSurvivesTheShell) {
  for (const std::string word : {"plain", "two words", "it's", "a\"b", "$HOME", "`x`", "back\\slash", "", "new\nline"}) {
    const std::string command = "printf %s " + shell_quote(word);
    FILE* shell = ::popen(command.c_str(), "r");
    ASSERT_NE(shell, nullptr);
    std::string printed;
    char buffer[256];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, shell)) > 0;) printed.append(buffer, n);
    ASSERT_EQ(::pclose(shell), 0) << command;
    EXPECT_EQ(printed, word) << command;
  }
  EXPECT_EQ(shell_quote("out/sweep-1,2:x=y"), "out/sweep-1,2:x=y");
}

TEST(SweepSlurmScripts, APrintedCommandLinePastedIntoAShellGivesBackItsWords) {
  const std::vector<std::string> words = {"printf", "%s|", "a3rig", "--scenario", "my $(touch /tmp/a3rig-pwned) 'x'.json",
                                          "--out", "out/sweep cells;rm -rf x"};
  FILE* shell = ::popen(shell_command(words).c_str(), "r");
  ASSERT_NE(shell, nullptr);
  std::string printed;
  char buffer[256];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, shell)) > 0;) printed.append(buffer, n);
  ASSERT_EQ(::pclose(shell), 0);
  EXPECT_EQ(printed, "a3rig|--scenario|my $(touch /tmp/a3rig-pwned) 'x'.json|--out|out/sweep cells;rm -rf x|");
}

TEST(SweepSlurmScripts, BadOptionsAreNamed) {
  SlurmJobOptions job = example_job();
  job.out_dir = "relative/out";
  EXPECT_THROW(array_script(job), std::invalid_argument);
  job = example_job();
  job.shards = 0;
  EXPECT_THROW(merge_script(job), std::invalid_argument);
  job = example_job();
  job.partition = "a\nb";
  try {
    (void)array_script(job);
    FAIL() << "a line break went onto an #SBATCH line";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("line break"), std::string::npos) << e.what();
  }
}

// Records the sbatch calls and answers from a list.
class FakeSbatch : public CommandRunner {
 public:
  explicit FakeSbatch(std::vector<CapturedOutput> answers) : answers_(std::move(answers)) {}
  CapturedOutput run(const std::vector<std::string>& argv) override {
    calls.push_back(argv);
    return answers_.at(calls.size() - 1);
  }
  std::vector<std::vector<std::string>> calls;

 private:
  std::vector<CapturedOutput> answers_;
};

TEST(SweepSlurmSubmit, TheMergeJobRunsAfterAnyEndOfTheArray) {
  FakeSbatch sbatch({{0, "4711;a3test\n", ""}, {0, "4712\n", ""}});
  const SlurmSubmission ids = submit_slurm_jobs("/o", sbatch);
  EXPECT_EQ(ids.array_job_id, "4711");
  EXPECT_EQ(ids.merge_job_id, "4712");
  ASSERT_EQ(sbatch.calls.size(), 2u);
  EXPECT_EQ(sbatch.calls[0], (std::vector<std::string>{"sbatch", "--parsable", "/o/slurm/array.sbatch"}));
  EXPECT_EQ(sbatch.calls[1], (std::vector<std::string>{"sbatch", "--parsable", "--dependency=afterany:4711",
                                                       "/o/slurm/merge.sbatch"}));
}

TEST(SweepSlurmSubmit, AFailingSbatchIsReportedWithItsStderr) {
  FakeSbatch sbatch({{1, "", "sbatch: error: invalid partition specified: gpu\n"}});
  try {
    (void)submit_slurm_jobs("/o", sbatch);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("invalid partition specified: gpu"), std::string::npos) << what;
    EXPECT_NE(what.find("exit status 1"), std::string::npos) << what;
  }
  EXPECT_EQ(sbatch.calls.size(), 1u);
}

TEST(SweepSlurmSubmit, AFailedMergeSubmissionGivesTheArrayIdAndTheCommandByHand) {
  FakeSbatch sbatch({{0, "4711\n", ""}, {1, "", "sbatch: error: Batch job submission failed"}});
  try {
    (void)submit_slurm_jobs("/o", sbatch);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("job array 4711 is submitted"), std::string::npos) << what;
    EXPECT_NE(what.find("sbatch --parsable --dependency=afterany:4711 /o/slurm/merge.sbatch"), std::string::npos) << what;
  }
}

TEST(SweepSlurmSubmit, JobIdsAreParsedOrRefused) {
  EXPECT_EQ(parse_job_id("123\n"), "123");
  EXPECT_EQ(parse_job_id("123;cluster"), "123");
  EXPECT_THROW(parse_job_id("Submitted batch job 123"), std::runtime_error);
  EXPECT_THROW(parse_job_id(""), std::runtime_error);
}

TEST(SweepSlurmSubmit, AProgramNotOnThePathIsNamed) {
  ProcessCommandRunner runner;
  try {
    (void)runner.run({"a3-no-such-sbatch-program"});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "a3-no-such-sbatch-program: not found on PATH");
  }
  const CapturedOutput both = runner.run({"sh", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_EQ(both.exit_status, 3);
  EXPECT_EQ(both.out, "out\n");
  EXPECT_EQ(both.err, "err\n");
}

TEST(SweepSlurmSubmit, ScriptsAreWrittenExecutableBesideTheLogsFolder) {
  SlurmJobOptions job = example_job();
  job.out_dir = fs::temp_directory_path() / ("a3-slurm-scripts-" + std::to_string(::getpid()));
  fs::remove_all(job.out_dir);
  write_slurm_scripts(job);
  std::ifstream array(array_script_path(job.out_dir));
  std::stringstream text;
  text << array.rdbuf();
  EXPECT_EQ(text.str(), array_script(job));
  EXPECT_TRUE(fs::is_directory(job.out_dir / "slurm" / "logs"));
  EXPECT_EQ(::access(merge_script_path(job.out_dir).c_str(), X_OK), 0);
  fs::remove_all(job.out_dir);
}

TEST(SweepSlurmMerge, MissingShardsAreTheOnesWithoutAResultsFile) {
  const fs::path out = fs::temp_directory_path() / ("a3-slurm-missing-" + std::to_string(::getpid()));
  fs::remove_all(out);
  fs::create_directories(out);
  for (const int i : {0, 2}) std::ofstream(results_path(out, Shard{i, 4})) << "x\n";
  EXPECT_EQ(missing_shards(out, 4), (std::vector<int>{1, 3}));
  std::ofstream(out / "results.csv") << "x\n";
  EXPECT_EQ(missing_shards(out, 1), std::vector<int>{});
  fs::remove_all(out);
}

}  // namespace
}  // namespace a3::rigs::sweep
