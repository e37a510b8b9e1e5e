// `a3rig serve-model`: a local OpenAI-compatible model server (agent/model_server/) for running
// everything without a network, and for testing LLM clients against a slow or failing model.
#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>

#include "agent/model_server/corpus_responder.hpp"
#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_file_responder.hpp"
#include "agent/model_server/scripted_responder.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/http_limit_flags.hpp"
#include "rigs/cli/flag_checks.hpp"
#include "rigs/cli/signal_stop.hpp"

namespace a3::rigs {
namespace {

namespace ms = agent::model_server;
using ResponderFactory = std::function<std::unique_ptr<ms::ModelResponder>()>;

// One `--responder NAME`: its help line, and a function adding its flags (to an option group of
// its own; the options struct lives in the responder's header) that returns the factory building
// the responder once the command line is parsed.
struct ResponderChoice {
  std::string help;
  std::function<ResponderFactory(CLI::Option_group& flags)> add_flags;
};

ResponderChoice reply_file_choice() {
  return {"every request is answered with a file's content (several --reply-file / --reply-text: in turn, cycled)",
          [](CLI::Option_group& flags) {
            auto o = std::make_shared<ms::ReplyFileResponderOptions>();
            flags.add_option("--reply-file", o->files, "a file whose whole content is one reply (repeatable)");
            flags.add_option("--reply-text", o->texts, "a reply given here (repeatable; after the files)");
            return ResponderFactory([o] { return ms::make_reply_file_responder(*o); });
          }};
}

ResponderChoice corpus_choice() {
  return {"replays a recorded α³-Bench model folder to `a3rig generate`: each request gets the recorded episode of "
          "its scenario and seed, with the recorded gen_time_s as latency (--latency recorded, scaled by "
          "--time-scale) and the recorded token usage; recorded retries and failure stubs are replayed as failed "
          "attempts (the public folders hold seed 42 only, as ep-00: run generate with --seeds 42)",
          [](CLI::Option_group& flags) {
            auto o = std::make_shared<ms::CorpusResponderOptions>();
            flags.add_option("--corpus", o->folder,
                             "a model's folder of sc-XXXX-ep-YY.json files, e.g. "
                             "alphabench/eval_runs/openai/chatgpt-4o-latest/uav");
            return ResponderFactory([o] { return ms::make_corpus_responder(*o); });
          }};
}

ResponderChoice scripted_choice() {
  return {"the rig's scripted policy answers the llm agent's turns (closed-loop `a3rig run --agent llm` offline): "
          "as the JSON text protocol, or with `tools` as tool_calls (one per action, then report_turn); any other "
          "client gets a generic answer (a call of the chosen tool with arguments made from its schema, or a short "
          "text)",
          [](CLI::Option_group&) { return ResponderFactory([] { return std::make_unique<ms::ScriptedResponder>(); }); }};
}

// The responders. To add one: write a <name>_choice() like reply_file_choice() above (its flags
// go into its own option group, its options struct into its own header) and add one line here.
std::map<std::string, ResponderChoice> responder_choices() {
  std::map<std::string, ResponderChoice> choices;
  choices["corpus"] = corpus_choice();
  choices["reply-file"] = reply_file_choice();
  choices["scripted"] = scripted_choice();
  return choices;
}

struct ServeArgs {
  std::string responder;
  ms::ModelServerOptions server;
  std::string ready_file;
  std::map<std::string, ResponderFactory> factories;
  std::map<std::string, CLI::Option_group*> groups;
};

void write_ready_file(const std::string& path, int port) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << port << "\n";
    if (!out) throw std::runtime_error("--ready-file " + path + ": cannot write " + tmp);
  }
  std::filesystem::rename(tmp, path);
}

int serve(ServeArgs& args) {
  // Another responder's flags are a mistake: say so rather than ignore them.
  for (const auto& [name, group] : args.groups) {
    if (name == args.responder) continue;
    for (const CLI::Option* opt : group->get_options()) {
      if (opt->count() > 0) {
        std::fprintf(stderr, "a3rig serve-model: %s is an option of --responder %s, not %s\n",
                     opt->get_name().c_str(), name.c_str(), args.responder.c_str());
        return 2;
      }
    }
  }
  std::unique_ptr<ms::ModelServer> server;
  try {
    server = std::make_unique<ms::ModelServer>(args.factories.at(args.responder)(), args.server);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "a3rig serve-model: %s\n", e.what());
    return 2;
  }
  if (!args.ready_file.empty()) {
    std::error_code ec;
    std::filesystem::remove(args.ready_file, ec);  // a stale one would announce the wrong port
  }
  std::signal(SIGPIPE, SIG_IGN);
  install_stop_signals();
  try {
    server->start();
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "a3rig serve-model: %s\n", e.what());
    return 1;
  }
  const auto started = std::chrono::steady_clock::now();
  std::string faults;
  if (args.server.fail_rate > 0.0 || args.server.fail_first > 0) {
    faults = ", failing " + (args.server.fail_first > 0 ? "the first " + std::to_string(args.server.fail_first) + " requests" : std::string()) +
             (args.server.fail_first > 0 && args.server.fail_rate > 0.0 ? " and " : "") +
             (args.server.fail_rate > 0.0 ? std::to_string(args.server.fail_rate) + " of them" : std::string()) +
             " with " + std::to_string(args.server.fail_status);
  }
  if (args.server.max_concurrency > 0) faults += ", at most " + std::to_string(args.server.max_concurrency) + " at once";
  if (!args.server.require_key_env.empty()) faults += ", key required ($" + args.server.require_key_env + ")";
  std::printf("serving %s on %s (latency %s%s)\n", server->responder_name().c_str(), server->base_url().c_str(),
              server->latency_model().describe().c_str(), faults.c_str());
  std::fflush(stdout);
  try {
    if (!args.ready_file.empty()) write_ready_file(args.ready_file, server->port());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "a3rig serve-model: %s\n", e.what());
    server->stop();
    return 2;
  }

  while (!stop_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  server->stop();
  if (!args.ready_file.empty()) {
    std::error_code ec;
    std::filesystem::remove(args.ready_file, ec);
  }
  const ms::ModelServerStats s = server->stats();
  const double up_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf(
      "stopped after %.1f s: %llu requests, %llu answered (%lld prompt + %lld completion tokens, %.1f s of latency "
      "applied), %llu bad, %llu unauthorized, %llu injected failures, %llu refused busy, %llu responder errors\n",
      up_s, static_cast<unsigned long long>(s.requests), static_cast<unsigned long long>(s.answered),
      static_cast<long long>(s.prompt_tokens), static_cast<long long>(s.completion_tokens), s.latency_applied_s,
      static_cast<unsigned long long>(s.bad_requests), static_cast<unsigned long long>(s.unauthorized),
      static_cast<unsigned long long>(s.injected_failures), static_cast<unsigned long long>(s.refused_busy),
      static_cast<unsigned long long>(s.responder_errors));
  std::fflush(stdout);
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("50-serve-model", [](CLI::App& app) {
  auto args = std::make_shared<ServeArgs>();
  const auto choices = responder_choices();
  std::string names, responder_help = "what answers the requests:";
  for (const auto& [name, choice] : choices) {
    names += (names.empty() ? "" : ", ") + name;
    responder_help += "\n  " + name + ": " + choice.help;
  }
  CLI::App* cmd = app.add_subcommand(
      "serve-model",
      "Serve an OpenAI-compatible chat-completions API (POST /v1/chat/completions, GET /v1/models, GET "
      "/v1/models/{id}) on this host, answered by a local responder after a chosen latency: run LLM agents and "
      "`a3rig generate` without a network, or test an LLM client against a slow, failing or rate-limiting model. "
      "Honours tools / tool_choice (none, auto, required, a named function), parallel_tool_calls, response_format "
      "(text, json_object, json_schema), n (1-8) and stream: true (server-sent chat.completion.chunk events, usage "
      "with stream_options.include_usage; the first chunk after half the latency, the rest spread over the other "
      "half). What it cannot honour (logprobs, audio, other tool types, ...) is a 400 naming the field; a body "
      "that is not JSON is a 415; one without Content-Length a 411, a malformed one a 400, one over 32 MiB a 413; a "
      "request whose head or body comes too late a 408 (--header-timeout, --body-timeout); a connection beyond "
      "--max-connections a 503. Errors are OpenAI's {\"error\": {message, type, param, code}}. Point a client "
      "at http://HOST:PORT/v1 (A3_LLM_BASE_URL). Stops on Ctrl-C or SIGTERM. Exit status: 0 stopped, 1 cannot "
      "listen, 2 bad usage.");
  ms::ModelServerOptions& o = args->server;
  std::vector<std::string> name_list;
  for (const auto& [name, choice] : choices) name_list.push_back(name);
  cmd->add_option("--responder", args->responder, responder_help)->required()->check(CLI::IsMember(name_list));
  cmd->add_option("--host", o.host, "address to listen on (default 127.0.0.1; 0.0.0.0: every interface)");
  cmd->add_option("--port", o.port, "port (default 8088; 0: any free port, printed and written to --ready-file)")
      ->check(a3::rigs::between(0, 65535));
  cmd->add_option("--latency", o.latency,
                  "wait before answering (default recorded): recorded (the responder's recorded latency, 0 when it "
                  "has none); a distribution per request: S, fixed:S, uniform:A,B, normal:MEAN,SD, "
                  "lognormal:MEDIAN,SIGMA, exp:MEAN; model:NAME (a model of the paper, per agent turn), "
                  "model-episode:NAME (per whole episode); tokens:PREFILL,DECODE[,TTFT] (TTFT + prompt tokens / "
                  "PREFILL + completion tokens / DECODE, tokens per second)");
  cmd->add_option("--time-scale", o.time_scale, "multiplies every latency (default 1; 0.1: ten times faster)")
      ->check(a3::rigs::non_negative());
  cmd->add_option("--seed", o.seed, "seed of the latency and fail-rate draws (default 42)");
  cmd->add_option("--fail-rate", o.fail_rate, "probability that a chat request fails on purpose (default 0)")
      ->check(a3::rigs::between(0.0, 1.0));
  cmd->add_option("--fail-first", o.fail_first, "the first N chat requests fail on purpose (default 0)")
      ->check(a3::rigs::non_negative());
  cmd->add_option("--fail-status", o.fail_status, "HTTP status of those failures: 429 (default), 500, 502, 503, 504")
      ->check(CLI::IsMember({429, 500, 502, 503, 504}));
  cmd->add_option("--retry-after", o.retry_after_s,
                  "Retry-After seconds sent with failures and busy refusals (default 1; 0: no header)")
      ->check(a3::rigs::non_negative());
  cmd->add_option("--max-concurrency", o.max_concurrency,
                  "chat requests answered at once; more get 429 with Retry-After (default 0: no limit)")
      ->check(a3::rigs::non_negative());
  cmd->add_option("--require-key-env", o.require_key_env,
                  "require Authorization: Bearer <the value of this environment variable> (401 otherwise); the "
                  "key itself is never given on the command line nor logged");
  cmd->add_option("--model-id", o.model_ids,
                  "model ids GET /v1/models lists and GET /v1/models/{id} knows (repeatable; default the responder's "
                  "name)");
  add_http_limit_flags(*cmd, o.http_limits, "--max-connections,--threads");  // --threads: its name before 2026-11
  add_http_origin_flags(*cmd, o.http_origins);
  cmd->add_option("--ready-file", args->ready_file,
                  "once listening, write the port to this file (removed on stop), for scripts to wait on");
  cmd->add_flag("-q,--quiet", o.quiet, "no line per request");
  for (const auto& [name, choice] : choices) {
    CLI::Option_group* group = cmd->add_option_group(name + " responder");
    args->groups[name] = group;
    args->factories[name] = choice.add_flags(*group);
  }
  cmd->callback([args] { command_exit_status() = serve(*args); });
});

}  // namespace a3::rigs
