// A fault-injecting OpenAI-compatible server for the client's tests: cpp-httplib on 127.0.0.1,
// a port of its own, answering each POST /v1/chat/completions with what the test's script says
// (status, body, headers, a delay) and recording every request it received.
#pragma once

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace a3::test {

struct ScriptedReply {
  int status = 200;
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers = {};
  double delay_s = 0.0;
};

struct RecordedRequest {
  nlohmann::json body;        // discarded when not JSON
  std::string authorization;  // the Authorization header, "" when absent
  int remote_port = 0;        // the client's port: the same on a kept-alive connection
};

// {"id", "object", "model", "choices": [{"message": {"role", "content"}, "finish_reason"}], "usage"}
inline std::string completion_body(const nlohmann::json& content, const nlohmann::json& usage = nullptr,
                                   const std::string& model = "test-model") {
  nlohmann::json body = {{"id", "chatcmpl-1"},
                         {"object", "chat.completion"},
                         {"created", 1700000000},
                         {"model", model},
                         {"choices",
                          {{{"index", 0},
                            {"message", {{"role", "assistant"}, {"content", content}}},
                            {"finish_reason", "stop"}}}}};
  if (!usage.is_null()) body["usage"] = usage;
  return body.dump();
}

class ScriptedOpenAiServer {
 public:
  // The script gets each request and its index (0 for the first) and says how to answer.
  using Script = std::function<ScriptedReply(const RecordedRequest& request, int index)>;

  explicit ScriptedOpenAiServer(Script script) : script_(std::move(script)) {
    server_.set_keep_alive_timeout(1);
    server_.Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) {
      RecordedRequest r;
      r.body = nlohmann::json::parse(req.body, nullptr, false);
      r.authorization = req.get_header_value("Authorization");
      r.remote_port = req.remote_port;
      int index;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        index = static_cast<int>(requests_.size());
        requests_.push_back(r);
      }
      const ScriptedReply reply = script_(r, index);
      if (reply.delay_s > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(reply.delay_s));
      res.status = reply.status;
      for (const auto& [name, value] : reply.headers) res.set_header(name, value);
      res.set_content(reply.body, "application/json");
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    if (port_ <= 0) throw std::runtime_error("scripted server: cannot bind 127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }

  // Answers in order; the last reply repeats.
  static Script sequence(std::vector<ScriptedReply> replies) {
    return [replies = std::move(replies)](const RecordedRequest&, int index) {
      return replies[std::min<std::size_t>(static_cast<std::size_t>(index), replies.size() - 1)];
    };
  }

  ~ScriptedOpenAiServer() {
    server_.stop();
    if (thread_.joinable()) thread_.join();
  }

  int port() const { return port_; }
  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }
  std::vector<RecordedRequest> requests() {
    std::lock_guard<std::mutex> lock(mutex_);
    return requests_;
  }

 private:
  Script script_;
  httplib::Server server_;
  int port_ = 0;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<RecordedRequest> requests_;
};

}  // namespace a3::test
