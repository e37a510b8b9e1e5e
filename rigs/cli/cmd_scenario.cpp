// `a3rig scenario generate`: writes procedurally generated missions (rigs/generator/scenario_generator.hpp)
// as scenario files, one to -o or stdout, or --count of them (seeds SEED.. SEED+K-1) to --out-dir.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/generator/scenario_generator.hpp"

namespace a3::rigs {
namespace {

struct GenerateArgs {
  uint64_t seed = 1;
  std::string difficulty = "medium";
  std::vector<std::string> knobs;  // knob=value
  std::string out_file;            // empty: stdout
  int count = 0;                   // > 0: that many files in out_dir
  std::string out_dir;
};

std::string spec_for(const GenerateArgs& args, uint64_t seed) {
  std::string spec = "gen:" + std::to_string(seed) + ":" + args.difficulty;
  for (const auto& k : args.knobs) spec += "+" + k;
  return spec;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text << "\n";
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string document_text(const std::string& spec) {
  return generate_scenario_json(parse_generator_spec(spec)).dump(2);
}

int run_generate(const GenerateArgs& args) {
  if (args.count > 0) {
    if (args.out_dir.empty()) throw std::invalid_argument("--count needs --out-dir");
    std::filesystem::create_directories(args.out_dir);
    for (int i = 0; i < args.count; ++i) {
      const uint64_t seed = args.seed + static_cast<uint64_t>(i);
      const auto path = std::filesystem::path(args.out_dir) / ("gen-" + std::to_string(seed) + "-" + args.difficulty + ".json");
      write_text(path, document_text(spec_for(args, seed)));
      std::printf("%s  %s\n", path.c_str(), spec_for(args, seed).c_str());
    }
    return 0;
  }
  const std::string text = document_text(spec_for(args, args.seed));
  if (args.out_file.empty()) {
    std::printf("%s\n", text.c_str());
  } else {
    write_text(args.out_file, text);
    std::printf("%s  %s\n", args.out_file.c_str(), spec_for(args, args.seed).c_str());
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("12-scenario", [](CLI::App& app) {
  CLI::App* scenario = app.add_subcommand("scenario", "Scenario tools: `a3rig scenario generate`.");
  scenario->require_subcommand(1);
  auto args = std::make_shared<GenerateArgs>();
  CLI::App* cmd = scenario->add_subcommand(
      "generate",
      "Write a procedurally generated mission as a scenario file (the format of rigs/scenarios/), valid by "
      "construction and checked as a file is. The same seed and knobs always give the same file; `--scenario "
      "gen:SEED:DIFFICULTY+knob=value...` flies it without a file (docs/generated-missions.md). Exit status: 0 "
      "written, 2 bad knobs or usage.");
  cmd->add_option("--seed", args->seed, "the mission's seed (default 1); with --count the first of the seeds");
  cmd->add_option("--difficulty", args->difficulty, "easy, medium (default) or hard: the knobs' preset")
      ->check(CLI::IsMember(difficulty_names()));
  cmd->add_option("--knob", args->knobs,
                  "knob=value over the preset, repeatable: " + knob_names());
  cmd->add_option("-o,--output", args->out_file, "the file to write (default: standard output)");
  cmd->add_option("--count", args->count, "write this many missions, seeds SEED..SEED+COUNT-1, into --out-dir")
      ->check(a3::rigs::between(1, 100000));
  cmd->add_option("--out-dir", args->out_dir, "folder for --count (created when absent): gen-<seed>-<difficulty>.json");
  cmd->callback([args] { command_exit_status() = run_generate(*args); });
});

}  // namespace a3::rigs
