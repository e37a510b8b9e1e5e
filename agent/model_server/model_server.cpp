// The OpenAI-compatible model server: routes, admission (authentication, body, validation,
// fault injection), latency, answers and streams, logging.
#include "agent/model_server/model_server.hpp"

#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>

#include "agent/http/guarded_server.hpp"
#include "agent/http/request_checks.hpp"
#include "agent/model_server/reply_shaping.hpp"
#include "agent/model_server/request_body.hpp"
#include "common/text_format.hpp"

namespace a3::agent::model_server {
namespace {

using nlohmann::json;
using SteadyClock = std::chrono::steady_clock;

using common::formatted;

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

void set_error(httplib::Response& res, const ApiError& error, double retry_after_s = 0.0) {
  res.status = error.status;
  if (retry_after_s > 0.0) res.set_header("Retry-After", std::to_string(static_cast<long>(std::ceil(retry_after_s))));
  res.set_content(openai_error_body(error).dump(-1, ' ', false, json::error_handler_t::replace), "application/json");
}

// Counts the chat requests being handled while it lives.
struct InFlight {
  std::atomic<int>& n;
  int now;
  explicit InFlight(std::atomic<int>& c) : n(c), now(++c) {}
  ~InFlight() { --n; }
};

int64_t usage_count(const json& usage, const char* key) {
  const auto it = usage.find(key);
  if (it == usage.end() || !it->is_number()) return -1;
  return it->is_number_float() ? static_cast<int64_t>(it->get<double>()) : it->get<int64_t>();
}

// The OpenAI error code of a refusal before any route (413 has its default).
std::optional<std::string> refusal_code(int status) {
  switch (status) {
    case 400: return "invalid_content_length";
    case 408: return "request_timeout";
    case 411: return "length_required";
    case 503: return "server_busy";
    default: return std::nullopt;
  }
}

}  // namespace

int64_t estimate_tokens(std::size_t characters) { return static_cast<int64_t>((characters + 3) / 4); }

std::size_t prompt_characters(const json& request) {
  std::size_t n = 0;
  if (!request.is_object()) return 0;
  if (request.contains("messages") && request["messages"].is_array()) {
    for (const auto& m : request["messages"]) {
      if (!m.is_object()) continue;
      if (m.contains("content")) n += content_characters(m["content"]);
      if (m.contains("tool_calls")) n += utf8_code_points(m["tool_calls"].dump());
    }
  }
  // The function definitions are part of the prompt a model reads (and is billed for).
  if (request.contains("tools") && request["tools"].is_array()) n += utf8_code_points(request["tools"].dump());
  return n;
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
    throw std::invalid_argument("fail rate " + formatted("%g", options_.fail_rate) + ": must be between 0 and 1");
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
  http::check_http_limits(options_.http_limits);
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

bool ModelServer::authorized() const {
  return required_key_.empty() || http::bearer_key_matches(http::GuardedServer::current_request_head(), required_key_);
}

bool ModelServer::wait_or_stop(double seconds) {
  std::unique_lock<std::mutex> lock(stop_mutex_);
  return !stop_cv_.wait_for(lock, std::chrono::duration<double>(std::max(0.0, seconds)), [this] { return stopping_; });
}

void ModelServer::start() {
  if (http_) throw std::logic_error("model server: already started");
  http_ = std::make_unique<http::GuardedServer>(
      options_.http_limits, options_.http_origins, options_.max_request_bytes,
      [this](const httplib::Request& req, httplib::Response& res, const http::HttpRefusal& refusal) {
        send_refusal(req, res, refusal);
      });
  http_->set_keep_alive_timeout(2);
  http_->set_keep_alive_max_count(1000);
  http_->set_tcp_nodelay(true);
  // The content-reader form of Post: httplib then leaves the body to us (no form parsing, whose
  // own 8 KiB limit answered 413 to form bodies).
  http_->Post("/v1/chat/completions", [this](const httplib::Request& req, httplib::Response& res,
                                             const httplib::ContentReader& reader) { handle_chat(req, res, reader); });
  http_->Get("/v1/models", [this](const httplib::Request&, httplib::Response& res) { handle_models(res); });
  http_->Get(R"(/v1/models/(.+))", [this](const httplib::Request& req, httplib::Response& res) { handle_model(req, res); });
  http_->set_error_handler(httplib::Server::HandlerWithResponse([this](const httplib::Request& req,
                                                                        httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    send_unrouted(req, res);
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
    set_error(res, {500, "internal error: " + what, std::nullopt, std::nullopt});
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


void ModelServer::send_error(httplib::Response& res, const ApiError& error, double retry_after_s, const std::string& what,
                             uint64_t ModelServerStats::*counter) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
    if (counter != nullptr) ++(stats_.*counter);
  }
  set_error(res, error, retry_after_s);
  log(what + " " + std::to_string(error.status) + " " + error.message);
}

void ModelServer::send_refusal(const httplib::Request& req, httplib::Response& res, const http::HttpRefusal& refusal) {
  const std::string what = req.method.empty() ? "(request head)" : req.method + " " + req.path;
  send_error(res, {refusal.status, refusal.message, std::nullopt, refusal_code(refusal.status)}, refusal.retry_after_s, what,
             refusal.status == 503 ? &ModelServerStats::refused_busy : &ModelServerStats::bad_requests);
}

void ModelServer::send_unrouted(const httplib::Request& req, httplib::Response& res) {
  const std::string route = req.method + " " + req.path;
  const std::string message =
      res.status == 404 ? "no route for " + route +
                              " (this server has POST /v1/chat/completions, GET /v1/models and GET /v1/models/{id})"
      : res.status == 413 ? "request body larger than " + std::to_string(options_.max_request_bytes) + " bytes"
                          : "malformed request: " + route + " could not be read (status " + std::to_string(res.status) + ")";
  send_error(res, {res.status, message, std::nullopt, std::nullopt}, 0.0, route, &ModelServerStats::bad_requests);
}

void ModelServer::handle_models(httplib::Response& res) {
  if (!authorized()) {
    send_error(res, {401, "missing or wrong API key: send Authorization: Bearer <key>", std::nullopt, std::nullopt}, 0.0,
               "GET /v1/models", &ModelServerStats::unauthorized);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
  }
  json data = json::array();
  for (const auto& id : options_.model_ids) {
    data.push_back({{"id", id}, {"object", "model"}, {"created", 0}, {"owned_by", "a3rig"}});
  }
  res.set_content(json({{"object", "list"}, {"data", data}}).dump(), "application/json");
}

void ModelServer::handle_model(const httplib::Request& req, httplib::Response& res) {
  const std::string id = req.matches[1];
  const std::string what = "GET /v1/models/" + id;
  if (!authorized()) {
    send_error(res, {401, "missing or wrong API key: send Authorization: Bearer <key>", std::nullopt, std::nullopt}, 0.0, what,
               &ModelServerStats::unauthorized);
    return;
  }
  if (std::find(options_.model_ids.begin(), options_.model_ids.end(), id) == options_.model_ids.end()) {
    send_error(res, {404, "the model '" + id + "' does not exist on this server (GET /v1/models lists them)", "model",
                     "model_not_found"}, 0.0, what, &ModelServerStats::bad_requests);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
  }
  res.set_content(json({{"id", id}, {"object", "model"}, {"created", 0}, {"owned_by", "a3rig"}}).dump(), "application/json");
}

std::optional<ApiError> ModelServer::admit_chat(const httplib::Request& req, const httplib::ContentReader& reader,
                                                json& request) {
  if (!authorized()) return ApiError{401, "missing or wrong API key: send Authorization: Bearer <key>", std::nullopt, std::nullopt};
  const std::string media = media_type(req.get_header_value("Content-Type"));
  if (auto e = form_body_error(media)) return e;
  std::string body;
  const bool read = reader([&body](const char* data, std::size_t n) {
    body.append(data, n);
    return true;
  });
  if (!read) {
    return ApiError{400, "request body cut short: fewer bytes arrived than its Content-Length announced", std::nullopt,
                    std::nullopt};
  }
  if (auto e = parse_json_body(body, media, request)) return e;
  return chat_request_error(request);
}

std::optional<ApiError> ModelServer::injected_failure(uint64_t& index) {
  std::lock_guard<std::mutex> lock(mutex_);
  index = chat_requests_++;
  const bool inject = index < static_cast<uint64_t>(options_.fail_first) ||
                      (options_.fail_rate > 0.0 && fault_rng_.bernoulli(options_.fail_rate));
  if (!inject) return std::nullopt;
  return ApiError{options_.fail_status,
                  "injected failure (--fail-rate / --fail-first), status " + std::to_string(options_.fail_status),
                  std::nullopt, std::nullopt};
}

std::vector<ResponderReply> ModelServer::answer(const json& request, const ChatOptions& options, uint64_t index,
                                                json& usage) {
  std::vector<ResponderReply> choices;
  int64_t prompt_tokens = -1, completion_tokens = 0;
  for (int i = 0; i < options.n; ++i) {
    ResponderReply reply;
    {
      std::lock_guard<std::mutex> lock(responder_mutex_);
      reply = responder_->respond(request);
    }
    shape_reply(reply, options, std::to_string(index) + (options.n > 1 ? "_" + std::to_string(i) : ""));
    // Counts the responder did not give are estimated from characters.
    const json u = reply.usage.is_object() ? reply.usage : json::object();
    if (prompt_tokens < 0) prompt_tokens = usage_count(u, "prompt_tokens");
    int64_t c = usage_count(u, "completion_tokens");
    if (c < 0) {
      std::size_t chars = utf8_code_points(reply.content);
      for (const auto& call : reply.tool_calls) chars += call.name.size() + call.arguments.size();
      c = estimate_tokens(chars);
    }
    completion_tokens += c;
    if (i == 0) usage = u;
    choices.push_back(std::move(reply));
  }
  if (prompt_tokens < 0) prompt_tokens = estimate_tokens(prompt_characters(request));
  usage["prompt_tokens"] = prompt_tokens;
  usage["completion_tokens"] = completion_tokens;
  usage["total_tokens"] = prompt_tokens + completion_tokens;
  return choices;
}

void ModelServer::send_stream(httplib::Response& res, std::vector<json> chunks, double gap_s) {
  auto events = std::make_shared<std::vector<std::string>>();
  for (const auto& c : chunks) events->push_back("data: " + c.dump(-1, ' ', false, json::error_handler_t::replace) + "\n\n");
  events->push_back("data: [DONE]\n\n");
  auto next = std::make_shared<std::size_t>(0);
  res.status = 200;
  res.set_header("Cache-Control", "no-cache");
  res.set_chunked_content_provider("text/event-stream", [this, events, next, gap_s](std::size_t, httplib::DataSink& sink) {
    if (*next > 0 && *next + 1 < events->size() && !wait_or_stop(gap_s)) return false;  // stopping: cut the stream
    const std::string& e = (*events)[(*next)++];
    if (!sink.write(e.data(), e.size())) return false;
    if (*next == events->size()) sink.done();
    return true;
  });
}

bool ModelServer::admitted(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader,
                           int in_flight, json& request, uint64_t& index) {
  const std::string route = "POST /v1/chat/completions";
  if (options_.max_concurrency > 0 && in_flight > options_.max_concurrency && authorized()) {
    res.set_header("Connection", "close");  // the body stays unread
    send_error(res, {429, "server busy: more than " + std::to_string(options_.max_concurrency) +
                              " requests at once (--max-concurrency)", std::nullopt, std::nullopt},
               options_.retry_after_s, route, &ModelServerStats::refused_busy);
    return false;
  }
  if (auto e = admit_chat(req, reader, request)) {
    if (e->status == 415) res.set_header("Connection", "close");  // the body stays unread
    send_error(res, *e, 0.0, route, e->status == 401 ? &ModelServerStats::unauthorized : &ModelServerStats::bad_requests);
    return false;
  }
  if (auto e = injected_failure(index)) {
    send_error(res, *e, options_.retry_after_s, route, &ModelServerStats::injected_failures);
    return false;
  }
  return true;
}

bool ModelServer::answered(const json& request, const ChatOptions& options, uint64_t index, httplib::Response& res,
                           std::vector<ResponderReply>& choices, json& usage) {
  const std::string what = "POST /v1/chat/completions model=" + request["model"].get<std::string>();
  try {
    choices = answer(request, options, index, usage);
    return true;
  } catch (const BadRequest& e) {
    send_error(res, {400, e.what(), e.param(), "invalid_value"}, 0.0, what, &ModelServerStats::bad_requests);
  } catch (const std::invalid_argument& e) {
    send_error(res, {400, e.what(), std::nullopt, std::nullopt}, 0.0, what, &ModelServerStats::bad_requests);
  } catch (const std::exception& e) {
    send_error(res, {500, responder_name_ + " responder failed: " + e.what(), std::nullopt, std::nullopt}, 0.0, what,
               &ModelServerStats::responder_errors);
  }
  return false;
}

void ModelServer::deliver(const ChatAnswer& a, httplib::Response& res) {
  const std::string model = a.request["model"].get<std::string>();
  double latency_s;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latency_s = latency_.latency_s(a.choices.front(), latency_rng_);
  }
  const double elapsed_s = std::chrono::duration<double>(SteadyClock::now() - a.started).count();
  const double first_s = a.options.stream ? latency_s * kFirstChunkShare : latency_s;
  if (!wait_or_stop(first_s - elapsed_s)) {
    send_error(res, {503, "server shutting down", std::nullopt, std::nullopt}, 0.0,
               "POST /v1/chat/completions model=" + model);
    return;
  }
  const CompletionHeader header{"chatcmpl-a3rig-" + std::to_string(a.index), static_cast<int64_t>(std::time(nullptr)), model};
  if (a.options.stream) {
    std::vector<json> chunks = completion_chunks(header, a.choices, a.options.include_usage ? a.usage : json());
    const double later_chunks = static_cast<double>(std::max<std::size_t>(1, chunks.size() - 1));
    send_stream(res, std::move(chunks), latency_s * (1.0 - kFirstChunkShare) / later_chunks);
  } else {
    res.status = 200;
    res.set_content(completion_json(header, a.choices, a.usage).dump(-1, ' ', false, json::error_handler_t::replace),
                    "application/json");
  }
  record_answer(a, latency_s);
}

void ModelServer::record_answer(const ChatAnswer& a, double latency_s) {
  const int64_t prompt_tokens = a.usage["prompt_tokens"], completion_tokens = a.usage["completion_tokens"];
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_.requests;
    ++stats_.answered;
    stats_.latency_applied_s += latency_s;
    stats_.prompt_tokens += prompt_tokens;
    stats_.completion_tokens += completion_tokens;
  }
  const double took_s = std::chrono::duration<double>(SteadyClock::now() - a.started).count();
  log("POST /v1/chat/completions 200 model=" + a.request["model"].get<std::string>() +
      (a.options.stream ? " stream" : "") + (a.options.n > 1 ? " n=" + std::to_string(a.options.n) : "") +
      " prompt_chars=" + std::to_string(prompt_characters(a.request)) + formatted(" latency=%.3fs", latency_s) +
      " tokens=" + std::to_string(prompt_tokens) + "+" + std::to_string(completion_tokens) +
      formatted(" took=%.3fs", took_s));
}

void ModelServer::handle_chat(const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& reader) {
  ChatAnswer a;
  a.started = SteadyClock::now();
  const InFlight in_flight(in_flight_);
  if (!admitted(req, res, reader, in_flight.now, a.request, a.index)) return;
  a.options = chat_options(a.request);
  if (!answered(a.request, a.options, a.index, res, a.choices, a.usage)) return;
  deliver(a, res);
}

}  // namespace a3::agent::model_server
