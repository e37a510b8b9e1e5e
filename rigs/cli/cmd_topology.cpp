// `a3rig topology [--scenario S]`: the rig's nodes and channels as `a3rig run` would build them
// (rig_topology.hpp), as text or Graphviz dot; exit status 1 when the graph has a problem (a
// subscription nobody publishes, a channel with two message types).
#include <CLI/CLI.hpp>

#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "rigs/cli/command_registry.hpp"
#include "rigs/generator/scenario_spec.hpp"
#include "rigs/run/rig_topology.hpp"
#include "rigs/scenario/scenario.hpp"
#include "rigs/scenario/shared_dir.hpp"

namespace a3::rigs {
namespace {

struct TopologyArgs {
  std::string scenario = "traffic-conflict";
  std::string runtime = "real";
  Sync sync = Sync::kLockstep;
  std::string format = "text";
};

int print_topology(const TopologyArgs& args) {
  RunOptions options;
  options.runtime = args.runtime == "virtual" ? Runtime::kVirtual : Runtime::kReal;
  options.sync = args.sync;
  const RigTopology topology = rig_topology(load_scenario_spec(args.scenario, default_shared_dir()), options);
  std::cout << (args.format == "dot" ? topology_dot(topology) : topology_text(topology));
  const auto problems = topology_problems(topology);
  for (const std::string& p : problems) std::cerr << "a3rig topology: problem: " << p << "\n";
  return problems.empty() ? 0 : 1;
}

}  // namespace

A3_REGISTER_COMMAND("80-topology", [](CLI::App& app) {
  auto args = std::make_shared<TopologyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "topology",
      "Print the rig's nodes and channels as `a3rig run` builds them: for each channel its message type, the "
      "nodes that publish it and those that subscribe (text), or the graph for Graphviz (--format dot: "
      "a3rig topology --format dot | dot -Tsvg > rig.svg). Exit status: 0 the graph is whole, 1 a problem (a "
      "subscription nobody publishes, a channel with two message types; each named on stderr), 2 bad usage.");
  cmd->add_option("--scenario", args->scenario, "a built-in scenario, a file, or gen:SEED (default traffic-conflict)");
  cmd->add_option("--runtime", args->runtime, "real (default: with the runtimes' own channels) or virtual")
      ->check(CLI::IsMember({"real", "virtual"}));
  cmd->add_option("--sync", args->sync, "real time: lockstep (default) or free")
      ->transform(CLI::CheckedTransformer(sync_by_name()))
      ->option_text("lockstep|free");
  cmd->add_option("--format", args->format, "text (default) or dot")->check(CLI::IsMember({"text", "dot"}));
  cmd->callback([args] { command_exit_status() = print_topology(*args); });
});

}  // namespace a3::rigs
