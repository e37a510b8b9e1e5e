// `a3rig generate`: the paper's offline benchmark (SPEC-alpha3.md §4): an LLM writes whole
// episodes from scenarios, validated, with up to 3 attempts, into the layout `a3rig score` reads.
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "agent/llm/llm_client.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/signal_stop.hpp"
#include "rigs/generate/generate_run.hpp"
#include "rigs/generate/generate_scenarios.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {
namespace {

namespace fs = std::filesystem;

struct GenerateArgs {
  std::vector<std::string> scenarios;
  std::vector<int64_t> seeds = {42, 77, 101, 2025, 1337};
  std::string out;
  std::string llm_base_url;
  std::string llm_model;
  std::string label;
  std::string domain = "uav";
  int jobs = 1;
  int max_tokens = 10000;
  double temperature = 0.0;
  double timeout_s = 600.0;
  int retries = 4;
  bool retry_failed = false;
  bool stream = false;
  bool quiet = false;
};

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
  }
  return buf;
}

// "provider/model": the model id when it has a provider part (OpenRouter ids such as
// openai/chatgpt-4o-latest, as the corpus's folders are), else the endpoint's provider and the id.
std::string default_label(const agent::llm::LlmEndpoint& endpoint) {
  if (endpoint.model.find('/') != std::string::npos) return endpoint.model;
  return endpoint.provider + "/" + endpoint.model;
}

// A label is two plain folder names.
std::string label_problem(const std::string& label) {
  const auto slash = label.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 == label.size() ||
      label.find('/', slash + 1) != std::string::npos) {
    return "must be PROVIDER/MODEL (two folder names), e.g. openai/gpt-4.1-mini";
  }
  for (const std::string& part : {label.substr(0, slash), label.substr(slash + 1)}) {
    if (part == "." || part == "..") return "must not use . or .. as a folder name";
  }
  return "";
}

void print_progress(const GenerateProgress& p) {
  const bool stub = p.outcome == GenerateProgress::Outcome::kFailureStub;
  for (const auto& error : p.attempt_errors) {
    std::fprintf(stderr, "  %s: %s\n", fs::path(p.file).filename().string().c_str(), error.c_str());
  }
  std::fprintf(stderr, "[%*zu/%zu] %s: %s, %d attempt%s, %.2f s, %lld tokens | elapsed %s, ETA %s\n",
               static_cast<int>(std::to_string(p.to_do).size()), p.done, p.to_do,
               fs::path(p.file).filename().string().c_str(), stub ? "FAILURE STUB" : "valid", p.attempts_used,
               p.attempts_used == 1 ? "" : "s", p.gen_time_s, static_cast<long long>(p.total_tokens),
               clock_text(p.elapsed_s).c_str(), clock_text(p.eta_s).c_str());
}

void print_summary(const GenerateRunSummary& summary) {
  std::fprintf(stderr,
               "a3rig generate: %zu planned: %zu kept (%zu valid, %zu failure stubs), %zu generated (%zu valid, %zu "
               "failure stubs, %lld tokens)%s in %.1f s; %zu left\n",
               summary.planned, summary.kept_valid + summary.kept_stubs, summary.kept_valid, summary.kept_stubs,
               summary.generated_valid + summary.generated_stubs, summary.generated_valid, summary.generated_stubs,
               static_cast<long long>(summary.total_tokens),
               summary.replaced_invalid > 0 ? (", " + std::to_string(summary.replaced_invalid) + " invalid files replaced").c_str() : "",
               summary.wall_s, summary.not_generated);
}

int run_generate_command(const GenerateArgs& args) {
  auto usage_error = [](const std::string& message) {
    std::fprintf(stderr, "a3rig generate: %s\n", message.c_str());
    return 2;
  };
  std::vector<GenerateScenario> scenarios;
  agent::llm::LlmEndpoint endpoint;
  GenerateRunOptions options;
  try {
    scenarios = load_generate_scenarios(args.scenarios);
    endpoint = agent::llm::endpoint_from_environment(args.llm_base_url, args.llm_model);
    endpoint.temperature = args.temperature;
    endpoint.max_tokens = args.max_tokens;
    endpoint.json_output = true;
    endpoint.total_timeout_s = args.timeout_s;
    endpoint.max_retries = args.retries;
    endpoint.stream = args.stream;
    (void)agent::llm::LlmClient(endpoint);  // checks the endpoint, fills the provider
    if (endpoint.provider.empty()) endpoint.provider = agent::llm::provider_from_base_url(endpoint.base_url);
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  }
  const std::string label = args.label.empty() ? default_label(endpoint) : args.label;
  if (const std::string problem = label_problem(label); !problem.empty()) {
    return usage_error("--label " + label + ": " + problem);
  }
  if (args.domain.empty() || args.domain.find('/') != std::string::npos || args.domain == "." || args.domain == "..") {
    return usage_error("--domain '" + args.domain + "': must be one folder name, e.g. uav");
  }
  options.scenarios = std::move(scenarios);
  options.seeds = args.seeds;
  options.output_dir = fs::path(args.out) / label / args.domain;
  options.model_label = label;
  options.jobs = args.jobs;
  options.retry_failed = args.retry_failed;

  const bool quiet = args.quiet;
  if (!quiet) {
    std::fprintf(stderr, "a3rig generate: %zu scenarios x %zu seeds from %s (model %s, temperature %g, max %d tokens, %d job%s) into %s\n",
                 options.scenarios.size(), options.seeds.size(), endpoint.base_url.c_str(), endpoint.model.c_str(),
                 endpoint.temperature, endpoint.max_tokens, options.jobs, options.jobs == 1 ? "" : "s",
                 options.output_dir.string().c_str());
  }
  auto on_episode = [quiet](const GenerateProgress& p) {
    if (!quiet) print_progress(p);
  };
  install_stop_signals();
  GenerateRunSummary summary;
  try {
    summary = run_generate(
        options, [endpoint] {
          auto client = std::make_shared<agent::llm::LlmClient>(endpoint);
          return GenerateChat([client](const std::vector<agent::llm::ChatMessage>& m) { return client->chat(m); });
        },
        on_episode, [] { return stop_requested(); });
  } catch (const std::invalid_argument& e) {
    return usage_error(e.what());
  }
  print_summary(summary);
  if (!summary.stop_error.empty()) {
    std::fprintf(stderr, "a3rig generate: stopped: %s\na3rig generate: run the same command again to continue\n",
                 summary.stop_error.c_str());
    return 1;
  }
  if (summary.stopped && summary.not_generated > 0) {
    std::fprintf(stderr, "a3rig generate: interrupted; run the same command again to continue\n");
    return 3;
  }
  std::printf("%s\n", options.output_dir.string().c_str());
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("45-generate", [](CLI::App& app) {
  auto args = std::make_shared<GenerateArgs>();
  std::string builtins;
  for (const auto& name : builtin_scenario_names()) builtins += (builtins.empty() ? "" : ", ") + name;
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "The paper's offline benchmark: for each scenario and episode seed, an OpenAI-compatible model writes a "
      "whole α³-Bench episode (temperature 0, at most 10 000 tokens); it is validated as `a3rig validate` does, "
      "with up to 3 attempts whose instructions get stricter (roles, then format); _meta records seed, ts, ts_iso, "
      "gen_time_s (first attempt to valid reply), attempts_used, generation_failed and the summed token usage, as "
      "the public corpus does; when every attempt fails, a failure stub is written (_meta: model, error, ts, "
      "generation_failed). Output: OUT/PROVIDER/MODEL/DOMAIN/sc-XXXX-ep-YY.json, which `a3rig score OUT` reads. "
      "Episode YY is the seed's position in --seeds (default 42, 77, 101, 2025, 1337 → ep-00..ep-04): the public "
      "corpus's files are seed 42 written as ep-00, so --seeds 42 reproduces its layout (and is what `serve-model --responder corpus` can answer). Resumable: "
      "valid episodes and failure stubs already in the folder are kept and invalid files generated again, so the "
      "same command continues an interrupted run (--retry-failed regenerates the stubs); files are written whole "
      "(temporary file, then rename). Ctrl-C finishes the episodes in progress and stops; a second Ctrl-C stops at "
      "once. HTTP errors that no attempt can fix (unreachable, 401, 403, 404, 429 or 5xx after --retries) stop the "
      "run without writing a stub; a refused request (e.g. 400) is a failed attempt. The API "
      "key is read only from the environment: A3_LLM_API_KEY, else the file named by A3_LLM_API_KEY_FILE, else "
      "OPENAI_API_KEY (none: no Authorization header, for local servers such as `a3rig serve-model`). Exit "
      "status: 0 every episode is there, 1 the endpoint failed or a file could not be written (run again to "
      "continue), 2 bad usage, 3 interrupted.");
  cmd->add_option("--scenarios", args->scenarios,
                  "scenarios (repeatable): a corpus model folder (every initial_state of its sc-XXXX-ep-YY.json "
                  "files, numbered as they are, e.g. alphabench/eval_runs/openai/chatgpt-4o-latest/uav), an "
                  "episode or scenario JSON file, or a built-in scenario (" + builtins + ")")
      ->required();
  cmd->add_option("--seeds", args->seeds, "episode seeds; episode YY is the YY-th (default 42 77 101 2025 1337)")
      ->delimiter(',');
  cmd->add_option("-o,--out", args->out, "output root: episodes go to OUT/PROVIDER/MODEL/DOMAIN/")->required();
  cmd->add_option("--llm-base-url", args->llm_base_url,
                  "the endpoint, e.g. https://api.openai.com/v1, https://openrouter.ai/api/v1, "
                  "http://127.0.0.1:8088/v1 (default $A3_LLM_BASE_URL)");
  cmd->add_option("--llm-model", args->llm_model,
                  "the model, e.g. gpt-4.1-mini, openai/chatgpt-4o-latest (default $A3_LLM_MODEL)");
  cmd->add_option("--label", args->label,
                  "PROVIDER/MODEL output folder and a stub's _meta.model (default: the model id when it has a '/', "
                  "else the endpoint's provider ($A3_LLM_PROVIDER or from the URL) / the model id)");
  cmd->add_option("--domain", args->domain, "domain folder (default uav)");
  cmd->add_option("-j,--jobs", args->jobs, "episodes generated at once (default 1)")->check(a3::rigs::between(1, 256));
  cmd->add_option("--max-tokens", args->max_tokens, "completion tokens per call (default 10000, as the paper)")
      ->check(a3::rigs::between(1, 1000000));
  cmd->add_option("--temperature", args->temperature, "sampling temperature (default 0, as the paper)")
      ->check(a3::rigs::between(0.0, 2.0));
  cmd->add_option("--timeout", args->timeout_s, "seconds one HTTP attempt may take (default 600)")
      ->check(a3::rigs::positive());
  cmd->add_option("--retries", args->retries,
                  "HTTP retries of one call on 429/5xx and network errors, with backoff (default 4); when they are "
                  "used up the run stops (exit 1) rather than write failure stubs for a broken endpoint")
      ->check(a3::rigs::between(0, 100));
  cmd->add_flag("--retry-failed", args->retry_failed, "generate again where a failure stub was written");
  cmd->add_flag("--llm-stream", args->stream, "stream the answers (stream: true, server-sent events)");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress lines");
  cmd->callback([args] { command_exit_status() = run_generate_command(*args); });
});

}  // namespace a3::rigs
