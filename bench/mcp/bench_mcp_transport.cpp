// The cost of the MCP protocol layer and its transports alone: tools/call of an instant fake
// tool (no vehicle, no link) in process (McpProtocol: parse, dispatch, the call worker's hop),
// over stdio (serve_stdio on two pipes, one JSON line each way) and over Streamable HTTP on
// loopback (cpp-httplib client, one kept-alive connection, application/json answers). Prints
// p50/p99/mean in microseconds; figures, never pass/fail.
// Usage: bench_mcp_transport [CALLS=5000]
#include <ext/stdio_filebuf.h>
#include <httplib.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <istream>
#include <string>
#include <thread>
#include <vector>

#include "agent/mcp/mcp_protocol.hpp"
#include "agent/mcp/mcp_server.hpp"

namespace {

using a3::agent::mcp::McpCallResult;
using a3::agent::mcp::McpProgress;
using a3::agent::mcp::McpResource;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

class InstantRig : public a3::agent::mcp::McpRig {
 public:
  std::string server_name() const override { return "bench"; }
  std::string server_version() const override { return "1"; }
  std::string instructions() const override { return "bench"; }
  json tools() const override { return json::array({{{"name", "read_telemetry"}, {"inputSchema", {{"type", "object"}}}}}); }
  std::vector<McpResource> resources() const override { return {}; }
  std::optional<std::string> read_resource(const std::string&) const override { return std::nullopt; }
  McpCallResult call_tool(const std::string&, const json&, const McpProgress&) override {
    return McpCallResult{{{"altitude_m", 50.0}, {"battery_pct", 97.0}, {"speed_mps", 8.0}}, "", false};
  }
  void client_closed() override {}
  bool episode_over() const override { return false; }
};

const std::string kInitialize =
    R"({"jsonrpc":"2.0","id":0,"method":"initialize","params":{"protocolVersion":"2025-06-18","capabilities":{},"clientInfo":{"name":"b","version":"1"}}})";
const std::string kCall = R"({"jsonrpc":"2.0","id":1,"method":"tools/call","params":{"name":"read_telemetry","arguments":{}}})";

void print_figures(const char* transport, std::vector<double> samples_us) {
  std::sort(samples_us.begin(), samples_us.end());
  const auto at = [&](double q) { return samples_us[std::min(samples_us.size() - 1, size_t(q * samples_us.size()))]; };
  double sum = 0;
  for (double s : samples_us) sum += s;
  std::printf("%-12s %8zu %9.1f %9.1f %9.1f\n", transport, samples_us.size(), at(0.5), at(0.99), sum / samples_us.size());
}

template <typename Once>
std::vector<double> time_calls(int calls, Once once) {
  for (int i = 0; i < 100; ++i) once();
  std::vector<double> samples_us;
  for (int i = 0; i < calls; ++i) {
    const auto start = Clock::now();
    once();
    samples_us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
  }
  return samples_us;
}

std::vector<double> in_process(int calls) {
  InstantRig rig;
  a3::agent::mcp::McpProtocol protocol(rig, [](const std::string&) {});
  protocol.handle_text(kInitialize, [](const json&) {});
  return time_calls(calls, [&] {
    std::promise<void> answered;
    protocol.handle_text(kCall, [&](const json&) { answered.set_value(); });
    answered.get_future().wait();
  });
}

std::vector<double> over_stdio(int calls) {
  int to_server[2], from_server[2];
  if (::pipe(to_server) != 0 || ::pipe(from_server) != 0) throw std::runtime_error("bench: pipe() failed");
  __gnu_cxx::stdio_filebuf<char> in_buf(to_server[0], std::ios::in);
  __gnu_cxx::stdio_filebuf<char> out_buf(from_server[1], std::ios::out);
  std::istream in(&in_buf);
  std::ostream out(&out_buf);
  InstantRig rig;
  a3::agent::mcp::McpServerOptions options;
  options.log = [](const std::string&) {};
  a3::agent::mcp::McpServer server(rig, options);
  std::thread serving([&] { server.serve_stdio(in, out); });
  FILE* replies = ::fdopen(from_server[0], "r");
  char* line = nullptr;
  size_t capacity = 0;
  const auto exchange = [&](const std::string& request) {
    const std::string text = request + "\n";
    if (::write(to_server[1], text.data(), text.size()) != ssize_t(text.size())) throw std::runtime_error("bench: write failed");
    if (::getline(&line, &capacity, replies) < 0) throw std::runtime_error("bench: no reply");
  };
  exchange(kInitialize);
  auto samples = time_calls(calls, [&] { exchange(kCall); });
  ::close(to_server[1]);
  serving.join();
  std::free(line);
  std::fclose(replies);
  return samples;
}

std::vector<double> over_http(int calls) {
  InstantRig rig;
  a3::agent::mcp::McpServerOptions options;
  options.log = [](const std::string&) {};
  a3::agent::mcp::McpServer server(rig, options);
  httplib::Client client("127.0.0.1", server.start_http());
  client.set_keep_alive(true);
  client.set_tcp_nodelay(true);
  const httplib::Headers accept{{"Accept", "application/json, text/event-stream"}};
  auto opened = client.Post("/mcp", accept, kInitialize, "application/json");
  if (!opened || opened->status != 200) throw std::runtime_error("bench: initialize over HTTP failed");
  const httplib::Headers session{{"Accept", "application/json, text/event-stream"},
                                 {"Mcp-Session-Id", opened->get_header_value("Mcp-Session-Id")},
                                 {"MCP-Protocol-Version", "2025-06-18"}};
  return time_calls(calls, [&] {
    auto reply = client.Post("/mcp", session, kCall, "application/json");
    if (!reply || reply->status != 200) throw std::runtime_error("bench: tools/call over HTTP failed");
  });
}

}  // namespace

int main(int argc, char** argv) {
  const int calls = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5000;
  std::printf("MCP tools/call of an instant tool (protocol layer and transport only), %d calls each\n", calls);
  std::printf("%-12s %8s %9s %9s %9s\n", "transport", "calls", "p50 us", "p99 us", "mean us");
  print_figures("in-process", in_process(calls));
  print_figures("stdio", over_stdio(calls));
  print_figures("http", over_http(calls));
  return 0;
}
