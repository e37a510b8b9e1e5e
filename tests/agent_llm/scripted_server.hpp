// `serve-model --responder scripted` in process, on a free loopback port, for the closed-loop
// `--agent llm` tests: the rig's scripted policy answering as a model would, after `latency`
// (a latency_model.hpp spec; serve-model's default when not given).
#pragma once

#include <memory>
#include <string>

#include "agent/model_server/model_server.hpp"
#include "agent/model_server/scripted_responder.hpp"

namespace a3::test {

struct ScriptedServer {
  agent::model_server::ModelServer server;
  explicit ScriptedServer(const std::string& latency = "recorded")
      : server(std::make_unique<agent::model_server::ScriptedResponder>(), options(latency),
               [](const std::string&) {}) {
    server.start();
  }
  ~ScriptedServer() { server.stop(); }
  static agent::model_server::ModelServerOptions options(const std::string& latency) {
    agent::model_server::ModelServerOptions o;
    o.port = 0;
    o.quiet = true;
    o.latency = latency;
    return o;
  }
};

}  // namespace a3::test
