// A tiny streaming chat-completions server for the client's tests: cpp-httplib on 127.0.0.1
// answering POST /v1/chat/completions with server-sent events written chunk by chunk (chunked
// transfer, a pause between chunks), then ending as the test says: cleanly, or by dropping the
// connection mid-stream. Records each request's body.
#pragma once

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace a3::test {

class SseTestServer {
 public:
  enum class End { kClean, kDropConnection };

  SseTestServer(std::vector<std::string> chunks, double pause_s, End end = End::kClean)
      : chunks_(std::move(chunks)), pause_s_(pause_s), end_(end) {
    server_.Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        bodies_.push_back(nlohmann::json::parse(req.body, nullptr, false));
      }
      auto next = std::make_shared<std::size_t>(0);
      res.set_chunked_content_provider("text/event-stream", [this, next](std::size_t, httplib::DataSink& sink) {
        if (*next < chunks_.size()) {
          if (*next > 0) std::this_thread::sleep_for(std::chrono::duration<double>(pause_s_));
          const std::string& c = chunks_[(*next)++];
          sink.write(c.data(), c.size());
          return true;
        }
        if (end_ == End::kDropConnection) return false;  // cancels: no final chunk, the connection closes
        sink.done();
        return true;
      });
    });
    port_ = server_.bind_to_any_port("127.0.0.1");
    if (port_ <= 0) throw std::runtime_error("SSE test server: cannot bind 127.0.0.1");
    thread_ = std::thread([this] { server_.listen_after_bind(); });
    while (!server_.is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ~SseTestServer() {
    server_.stop();
    thread_.join();
  }
  std::string base_url() const { return "http://127.0.0.1:" + std::to_string(port_) + "/v1"; }
  std::vector<nlohmann::json> bodies() {
    std::lock_guard<std::mutex> lock(mutex_);
    return bodies_;
  }

 private:
  std::vector<std::string> chunks_;
  double pause_s_;
  End end_;
  httplib::Server server_;
  int port_ = 0;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<nlohmann::json> bodies_;
};

}  // namespace a3::test
