// The cost of the LLM plumbing itself: an LlmClient (libcurl, kept-alive connection) against
// a ModelServer (cpp-httplib) on loopback with zero latency and the reply-file responder.
// Prints the round-trip percentiles of one client, one request at a time, and the requests per
// second with several clients at once (one thread and one client each).
// Usage: bench_model_server [--requests N] [--clients C] [--seconds S] [--reply-bytes B]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "agent/llm/llm_client.hpp"
#include "agent/model_server/model_server.hpp"
#include "agent/model_server/reply_file_responder.hpp"

namespace {

namespace ms = a3::agent::model_server;
namespace llm = a3::agent::llm;
using SteadyClock = std::chrono::steady_clock;

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())));
  return v[i];
}

llm::LlmEndpoint endpoint(const ms::ModelServer& server) {
  llm::LlmEndpoint e;
  e.base_url = server.base_url();
  e.model = "bench";
  e.max_retries = 0;
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"LLM client round trip and throughput against the local model server (loopback, zero latency)"};
  int requests = 2000;
  int clients = 4;
  double seconds = 5.0;
  int reply_bytes = 400;
  app.add_option("--requests", requests, "sequential requests for the round-trip percentiles (default 2000)");
  app.add_option("--clients", clients, "concurrent clients for the throughput (default 4)");
  app.add_option("--seconds", seconds, "length of the throughput run (default 5)");
  app.add_option("--reply-bytes", reply_bytes, "size of the reply's content (default 400, a typical agent turn)");
  CLI11_PARSE(app, argc, argv);

  ms::ModelServerOptions o;
  o.port = 0;
  o.quiet = true;
  o.latency = "fixed:0";
  o.http_limits.max_connections = std::max(16, clients + 2);
  std::string content = R"({"intent":"hold position","actions":[]})";
  content.resize(static_cast<std::size_t>(std::max(reply_bytes, 2)), ' ');
  ms::ModelServer server(std::make_unique<ms::ReplyFileResponder>(std::vector<std::string>{content}), o);
  server.start();
  const std::vector<llm::ChatMessage> messages = {
      {"system", std::string(1500, 's')},  // a system prompt with the tool catalogue, roughly
      {"user", "Status of the vehicle and the link, then the next action."}};

  // Round trip, one client, one request at a time.
  {
    llm::LlmClient client(endpoint(server));
    for (int i = 0; i < 50; ++i) client.chat(messages);  // warm-up (connection, allocator)
    std::vector<double> ms_each;
    ms_each.reserve(static_cast<std::size_t>(requests));
    int failed = 0;
    for (int i = 0; i < requests; ++i) {
      const auto t0 = SteadyClock::now();
      const llm::LlmCallResult r = client.chat(messages);
      ms_each.push_back(std::chrono::duration<double, std::milli>(SteadyClock::now() - t0).count());
      failed += r.ok ? 0 : 1;
    }
    std::printf("round trip, 1 client, %d requests (%d failed): p50 %.3f ms  p90 %.3f ms  p99 %.3f ms  max %.3f ms\n",
                requests, failed, percentile(ms_each, 0.50), percentile(ms_each, 0.90), percentile(ms_each, 0.99),
                *std::max_element(ms_each.begin(), ms_each.end()));
  }

  // Throughput, several clients at once.
  {
    std::atomic<bool> go{false}, stop{false};
    std::atomic<long> done{0}, failed{0};
    std::vector<std::thread> threads;
    for (int c = 0; c < clients; ++c) {
      threads.emplace_back([&] {
        llm::LlmClient client(endpoint(server));
        client.chat(messages);
        while (!go) std::this_thread::yield();
        while (!stop) {
          const bool ok = client.chat(messages).ok;
          if (!stop) (ok ? done : failed) += 1;
        }
      });
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const auto t0 = SteadyClock::now();
    go = true;
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    stop = true;
    const double elapsed_s = std::chrono::duration<double>(SteadyClock::now() - t0).count();
    for (auto& t : threads) t.join();
    std::printf("throughput, %d concurrent clients, %.1f s: %.0f requests/s (%ld answered, %ld failed)\n", clients,
                elapsed_s, static_cast<double>(done) / elapsed_s, done.load(), failed.load());
  }
  server.stop();
  return 0;
}
