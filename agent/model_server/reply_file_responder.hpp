// A responder that answers every request with a fixed reply: the content of a file, or several
// files (or texts) answered in turn, cycled. "What does my client do with this reply?" — and a
// way to test the server with nothing else. Token usage is estimated from characters (~4 per
// token, model_server.hpp estimate_tokens); it records no latency.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "agent/model_server/model_responder.hpp"

namespace a3::agent::model_server {

// `a3rig serve-model --responder reply-file` options.
struct ReplyFileResponderOptions {
  std::vector<std::string> files;  // each file's whole content is one reply
  std::vector<std::string> texts;  // replies given on the command line, after the files
};

class ReplyFileResponder final : public ModelResponder {
 public:
  // Throws std::invalid_argument when there is no reply or a reply is not UTF-8.
  explicit ReplyFileResponder(std::vector<std::string> replies);
  std::string name() const override { return "reply-file"; }
  ResponderReply respond(const nlohmann::json& request) override;
  std::size_t reply_count() const { return replies_.size(); }

 private:
  std::vector<std::string> replies_;
  std::atomic<std::size_t> next_{0};
};

// Reads the files (at most 16 MiB each); throws std::invalid_argument naming a file that cannot
// be read, is too large or is not UTF-8, or when no file and no text is given.
std::unique_ptr<ReplyFileResponder> make_reply_file_responder(const ReplyFileResponderOptions& options);

}  // namespace a3::agent::model_server
