// Running a short-lived program (sbatch) and capturing what it prints, behind an interface so
// that what is done with the output is tested without the program.
#pragma once

#include <string>
#include <vector>

namespace a3::rigs::sweep {

struct CapturedOutput {
  int exit_status = 0;  // the program's exit status; 128 + N when killed by signal N
  std::string out;
  std::string err;
};

class CommandRunner {
 public:
  virtual ~CommandRunner() = default;
  // argv[0] is looked up on PATH. Throws std::runtime_error "<argv[0]>: not found on PATH" when
  // it is not there, and naming the reason when it cannot be started.
  virtual CapturedOutput run(const std::vector<std::string>& argv) = 0;
};

// Starts the program (posix_spawnp), stdin from /dev/null, and reads its stdout and stderr to the end.
class ProcessCommandRunner : public CommandRunner {
 public:
  CapturedOutput run(const std::vector<std::string>& argv) override;
};

}  // namespace a3::rigs::sweep
