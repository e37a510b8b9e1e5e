// The OpenAI-compatible model server: routes, validation, authentication, fault injection,
// latency, logging.
#include "agent/model_server/model_server.hpp"

#include <httplib.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>

namespace a3::agent::model_server {
namespace {

using nlohmann::json;
using SteadyClock = std::chrono::steady_clock;

std::string fmt(const char* format, double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, format, x);
  return buf;
}

std::size_t utf8_code_points(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

std::size_t content_characters(const json& content) {
  if (content.is_string()) return utf8_code_points(content.get_ref<const std::string&>());
  std::size_t n = 0;
  if (content.is_array()) {
    for (const auto& part : content) {
      if (part.is_string()) n += utf8_code_points(part.get_ref<const std::string&>());
      if (part.is_object() && part.contains("text") && part["text"].is_string()) {
        n += utf8_code_points(part["text"].get_ref<const std::string&>());
      }
    }
  }
  return n;
}

const char* error_type(int status) {
  switch (status) {
    case 401: return "authentication_error";
    case 429: return "rate_limit_error";
    case 404: return "not_found_error";
    default: return status >= 500 ? "server_error" : "invalid_request_error";
  }
}

void set_error(httplib::Response& res, int status, const std::string& message, double retry_after_s = 0.0) {
  res.status = status;
  if (retry_after_s > 0.0) res.set_header("Retry-After", std::to_string(static_cast<long>(std::ceil(retry_after_s))));
  const json body = {{"error", {{"message", message}, {"type", error_type(status)}, {"code", status}}}};
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

int64_t usage_count(const json& usage, const char* key) {
  const auto it = usage.find(key);
  if (it == usage.end() || !it->is_number()) return -1;
  return it->is_number_float() ? static_cast<int64_t>(it->get<double>()) : it->get<int64_t>();
}

// Compares without stopping at the first difference (no timing hint about the key's characters).
bool constant_time_equal(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

}  // namespace

int64_t estimate_tokens(std::size_t characters) { return static_cast<int64_t>((characters + 3) / 4); }

std::size_t prompt_characters(const json& request) {
  std::size_t n = 0;
  if (request.is_object() && request.contains("messages") && request["messages"].is_array()) {
    for (const auto& m : request["messages"]) {
      if (m.is_object() && m.contains("content")) n += content_characters(m["content"]);
    }
  }
  return n;
}

std::string chat_request_problem(const json& request) {
  if (!request.is_object()) return "the request body must be a JSON object";
  const auto model = request.find("model");
  if (model == request.end()) return "'model' is required";
  if (!model->is_string() || model->get_ref<const std::string&>().empty()) return "'model' must be a non-empty string";
  const auto messages = request.find("messages");
  if (messages == request.end()) return "'messages' is required";
  if (!messages->is_array() || messages->empty()) return "'messages' must be a non-empty array";
  for (std::size_t i = 0; i < messages->size(); ++i) {
    const json& m = (*messages)[i];
    const std::string where = "messages[" + std::to_string(i) + "]";
    if (!m.is_object()) return where + " must be an object {role, content}";
    const auto role = m.find("role");
    if (role == m.end() || !role->is_string()) return where + ".role must be a string";
    const std::string& r = role->get_ref<const std::string&>();
    if (r != "system" && r != "user" && r != "assistant" && r != "tool" && r != "developer") {
      return where + ".role must be one of system, user, assistant, tool, developer (got '" + r + "')";
    }
    const auto content = m.find("content");
    if (content == m.end()) return where + ".content is required";
    const bool ok = content->is_string() || content->is_array() || (content->is_null() && r == "assistant");
    if (!ok) return where + ".content must be a string or an array of content parts";
    if (content->is_array()) {
      for (std::size_t j = 0; j < content->size(); ++j) {
        const json& part = (*content)[j];
        if (!part.is_string() && !(part.is_object() && part.contains("type") && part["type"].is_string())) {
          return where + ".content[" + std::to_string(j) + "] must be a content part {type, ...}";
        }
      }
    }
  }
  if (const auto t = request.find("temperature"); t != request.end() && !t->is_null()) {
    if (!t->is_number() || t->get<double>() < 0.0 || t->get<double>() > 2.0) {
      return "'temperature' must be a number between 0 and 2";
    }
  }
  for (const char* key : {"max_tokens", "max_completion_tokens"}) {
    if (const auto t = request.find(key); t != request.end() && !t->is_null()) {
      if (!t->is_number_integer() || t->get<int64_t>() < 1) return std::string("'") + key + "' must be an integer >= 1";
    }
  }
  if (const auto f = request.find("response_format"); f != request.end() && !f->is_null()) {
    if (!f->is_object() || !f->contains("type") || !(*f)["type"].is_string()) {
      return "'response_format' must be an object {\"type\": ...}";
    }
  }
  if (const auto s = request.find("stream"); s != request.end() && s->is_boolean() && s->get<bool>()) {
    return "'stream': true is not supported by this server";
  }
  return "";
}

ModelServer::ModelServer(std::unique_ptr<ModelResponder> responder, ModelServerOptions options, LogLine log)
    : responder_(std::move(responder)),
      options_(std::move(options)),
      latency_(LatencyModel::parse(options_.latency, options_.time_scale)),
      log_(std::move(log)),
      latency_rng_(common::RngStreams(options_.seed).stream("model_server.latency")),
      fault_rng_(common::RngStreams(options_.seed).stream("model_server.faults")) {
  if (!responder_) throw std::invalid_argument("model server: no responder");
  responder_name_ = responder_->name();
  if (options_.port < 0 || options_.port > 65535) {
    throw std::invalid_argument("port " + std::to_string(options_.port) + ": must be 0..65535 (0: any free port)");
  }
  if (!(options_.fail_rate >= 0.0 && options_.fail_rate <= 1.0)) {
    throw std::invalid_argument("fail rate " + fmt("%g", options_.fail_rate) + ": must be between 0 and 1");
  }
  if (options_.fail_first < 0) throw std::invalid_argument("fail-first: must be >= 0");
  const int s = options_.fail_status;
  if (s != 429 && s != 500 && s != 502 && s != 503 && s != 504) {
    throw std::invalid_argument("fail status " + std::to_string(s) + ": must be 429, 500, 502, 503 or 504");
  }
  if (!(options_.retry_after_s >= 0.0) || !std::isfinite(options_.retry_after_s)) {
    throw std::invalid_argument("retry-after: must be >= 0 s");
  }
  if (options_.max_concurrency < 0) throw std::invalid_argument("max concurrency: must be >= 0 (0: no limit)");
  if (options_.threads < 1) throw std::invalid_argument("threads: must be >= 1");
  if (!options_.require_key_env.empty()) {
    const char* key = std::getenv(options_.require_key_env.c_str());
    if (key == nullptr || *key == '\0') {
      throw std::invalid_argument("--require-key-env " + options_.require_key_env + ": the variable " +
                                  options_.require_key_env + " is not set (it holds the key clients must send)");
    }
    required_key_ = key;
  }
  if (options_.model_ids.empty()) options_.model_ids.push_back(responder_name_);
  if (!log_) {
    log_ = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  }
}

ModelServer::~ModelServer() { stop(); }

std::string ModelServer::base_url() const {
  const bool v6 = options_.host.find(':') != std::string::npos;
  return "http://" + (v6 ? "[" + options_.host + "]" : options_.host) + ":" + std::to_string(port_) + "/v1";
}

ModelServerStats ModelServer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

void ModelServer::log(const std::string& line) {
  if (options_.quiet) return;
  std::lock_guard<std::mutex> lock(log_mutex_);
  log_(line);
}

bool ModelServer::authorized(const httplib::Request& req) const {
  if (required_key_.empty()) return true;
  const std::string header = req.get_header_value("Authorization");
  const std::string prefix = "Bearer ";
  if (header.rfind(prefix, 0) != 0) return false;
  return constant_time_equal(header.substr(prefix.size()), required_key_);
}

bool ModelServer::wait_or_stop(double seconds) {
  std::unique_lock<std::mutex> lock(stop_mutex_);
  return !stop_cv_.wait_for(lock, std::chrono::duration<double>(std::max(0.0, seconds)), [this] { return stopping_; });
}

void ModelServer::start() {
  if (http_) throw std::logic_error("model server: already started");
  http_ = std::make_unique<httplib::Server>();
  const int threads = options_.threads;
  http_->new_task_queue = [threads] { return new httplib::ThreadPool(static_cast<std::size_t>(threads)); };
  http_->set_keep_alive_timeout(2);
  http_->set_keep_alive_max_count(1000);
  http_->set_payload_max_length(options_.max_request_bytes);
  http_->set_tcp_nodelay(true);
  http_->Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res) { handle_chat(req, res); });
  http_->Get("/v1/models", [this](const httplib::Request& req, httplib::Response& res) { handle_models(req, res); });
  http_->set_error_handler(httplib::Server::HandlerWithResponse([this](const httplib::Request& req,
                                                                        httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.requests;
      ++stats_.bad_requests;
    }
    const std::string message = res.status == 413 ? "request body larger than " +
                                                        std::to_string(options_.max_request_bytes) + " bytes"
                                                  : "no route for " + req.method + " " + req.path +
                                                        " (this server has POST /v1/chat/completions and GET /v1/models)";
    set_error(res, res.status, message);
    log(req.method + " " + req.path + " " + std::to_string(res.status) + " " + message);
    return httplib::Server::HandlerResponse::Handled;
  }));
  http_->set_exception_handler([this](const httplib::Request& req, httplib::Response& res, std::exception_ptr ep) {
    std::string what = "unknown error";
    try {
      if (ep) std::rethrow_exception(ep);
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
    set_error(res, 500, "internal error: " + what);
    log(req.method + " " + req.path + " 500 internal error: " + what);
  });

  // httplib's default adds SO_REUSEPORT, which lets a second server share a port in use: only
  // SO_REUSEADDR here, so a busy port is an error.
  http_->set_socket_options([](int sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  if (options_.port == 0) {
    port_ = http_->bind_to_any_port(options_.host);
  } else {
    port_ = http_->bind_to_port(options_.host, options_.port) ? options_.port : -1;
  }
  if (port_ <= 0) {
    http_.reset();
    port_ = 0;
    throw std::runtime_error("cannot listen on " + options_.host + ":" + std::to_string(options_.port) +
                             " (address in use, or not an address of this host?)");
  }
  thread_ = std::thread([this] { http_->listen_after_bind(); });
  // stop() before the accept loop runs would leave it running forever: wait until it does.
  while (!http_->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void ModelServer::stop() {
  {
    std::lock_guard<std::mutex> lock(stop_mutex_);
    stopping_ = true;
  }
  stop_cv_.notify_all();
  if (http_) http_->stop();
  if (thread_.joinable()) thread_.join();
}

void ModelServer::handle_models(const httplib::Request& req, httplib::Response& res) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
    if (!authorized(req)) ++stats_.unauthorized;
  }
  if (!authorized(req)) {
    set_error(res, 401, "missing or wrong API key: send Authorization: Bearer <key>");
    log("GET /v1/models 401 unauthorized");
    return;
  }
  json data = json::array();
  for (const auto& id : options_.model_ids) {
    data.push_back({{"id", id}, {"object", "model"}, {"created", 0}, {"owned_by", "a3rig"}});
  }
  res.set_content(json({{"object", "list"}, {"data", data}}).dump(), "application/json");
}

void ModelServer::handle_chat(const httplib::Request& req, httplib::Response& res) {
  const auto t0 = SteadyClock::now();
  const std::string route = "POST /v1/chat/completions";
  auto count = [this](uint64_t ModelServerStats::*field) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
    if (field != nullptr) ++(stats_.*field);
  };
  auto fail = [&](uint64_t ModelServerStats::*field, int status, const std::string& message, double retry_after_s,
                  const std::string& model) {
    count(field);
    set_error(res, status, message, retry_after_s);
    log(route + " " + std::to_string(status) + (model.empty() ? "" : " model=" + model) + " " + message);
  };

  if (!authorized(req)) {
    fail(&ModelServerStats::unauthorized, 401, "missing or wrong API key: send Authorization: Bearer <key>", 0.0, "");
    return;
  }
  struct InFlight {
    std::atomic<int>& n;
    int now;
    explicit InFlight(std::atomic<int>& c) : n(c), now(++c) {}
    ~InFlight() { --n; }
  } in_flight(in_flight_);
  if (options_.max_concurrency > 0 && in_flight.now > options_.max_concurrency) {
    fail(&ModelServerStats::refused_busy, 429,
         "server busy: more than " + std::to_string(options_.max_concurrency) + " requests at once (--max-concurrency)",
         options_.retry_after_s, "");
    return;
  }

  const json request = json::parse(req.body, nullptr, false);
  if (request.is_discarded()) {
    fail(&ModelServerStats::bad_requests, 400, "the request body is not JSON", 0.0, "");
    return;
  }
  if (const std::string problem = chat_request_problem(request); !problem.empty()) {
    fail(&ModelServerStats::bad_requests, 400, problem, 0.0, "");
    return;
  }
  const std::string model = request["model"].get<std::string>();

  bool inject = false;
  uint64_t index;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    index = chat_requests_++;
    inject = index < static_cast<uint64_t>(options_.fail_first) ||
             (options_.fail_rate > 0.0 && fault_rng_.bernoulli(options_.fail_rate));
  }
  if (inject) {
    fail(&ModelServerStats::injected_failures, options_.fail_status,
         "injected failure (--fail-rate / --fail-first), status " + std::to_string(options_.fail_status),
         options_.retry_after_s, model);
    return;
  }

  ResponderReply reply;
  try {
    std::lock_guard<std::mutex> lock(responder_mutex_);
    reply = responder_->respond(request);
  } catch (const std::invalid_argument& e) {
    fail(&ModelServerStats::bad_requests, 400, e.what(), 0.0, model);
    return;
  } catch (const std::exception& e) {
    fail(&ModelServerStats::responder_errors, 500, responder_name_ + " responder failed: " + e.what(), 0.0, model);
    return;
  }

  // Usage as OpenAI sends it; counts the responder did not give are estimated from characters.
  const std::size_t prompt_chars = prompt_characters(request);
  if (!reply.usage.is_object()) reply.usage = json::object();
  int64_t prompt_tokens = usage_count(reply.usage, "prompt_tokens");
  int64_t completion_tokens = usage_count(reply.usage, "completion_tokens");
  if (prompt_tokens < 0) reply.usage["prompt_tokens"] = prompt_tokens = estimate_tokens(prompt_chars);
  if (completion_tokens < 0) {
    reply.usage["completion_tokens"] = completion_tokens = estimate_tokens(utf8_code_points(reply.content));
  }
  if (usage_count(reply.usage, "total_tokens") < 0) reply.usage["total_tokens"] = prompt_tokens + completion_tokens;

  double latency_s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latency_s = latency_.latency_s(reply, latency_rng_);
  }
  const double elapsed_s = std::chrono::duration<double>(SteadyClock::now() - t0).count();
  if (!wait_or_stop(latency_s - elapsed_s)) {
    fail(nullptr, 503, "server shutting down", 0.0, model);
    return;
  }

  const json body = {{"id", "chatcmpl-a3rig-" + std::to_string(index)},
                     {"object", "chat.completion"},
                     {"created", static_cast<int64_t>(std::time(nullptr))},
                     {"model", model},
                     {"choices",
                      json::array({{{"index", 0},
                                    {"message", {{"role", "assistant"}, {"content", reply.content}}},
                                    {"finish_reason", reply.finish_reason.empty() ? "stop" : reply.finish_reason}}})},
                     {"usage", reply.usage}};
  res.status = 200;
  res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
    ++stats_.answered;
    stats_.latency_applied_s += latency_s;
    stats_.prompt_tokens += prompt_tokens;
    stats_.completion_tokens += completion_tokens;
  }
  const double took_s = std::chrono::duration<double>(SteadyClock::now() - t0).count();
  log(route + " 200 model=" + model + " prompt_chars=" + std::to_string(prompt_chars) +
      fmt(" latency=%.3fs", latency_s) + " tokens=" + std::to_string(prompt_tokens) + "+" +
      std::to_string(completion_tokens) + fmt(" took=%.3fs", took_s));
}

}  // namespace a3::agent::model_server
