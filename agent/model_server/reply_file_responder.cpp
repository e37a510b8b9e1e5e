// The reply-file responder.
#include "agent/model_server/reply_file_responder.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "agent/model_server/model_server.hpp"

namespace a3::agent::model_server {
namespace {

constexpr std::uintmax_t kMaxReplyBytes = 16u << 20;

bool is_utf8(const std::string& s) {
  try {
    (void)nlohmann::json(s).dump();
    return true;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

std::size_t code_points(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

}  // namespace

ReplyFileResponder::ReplyFileResponder(std::vector<std::string> replies) : replies_(std::move(replies)) {
  if (replies_.empty()) throw std::invalid_argument("reply-file responder: no reply (give --reply-file or --reply-text)");
  for (std::size_t i = 0; i < replies_.size(); ++i) {
    if (!is_utf8(replies_[i])) throw std::invalid_argument("reply " + std::to_string(i + 1) + " is not UTF-8 text");
  }
}

ResponderReply ReplyFileResponder::respond(const nlohmann::json& request) {
  ResponderReply reply;
  reply.content = replies_[next_.fetch_add(1) % replies_.size()];
  const int64_t prompt = estimate_tokens(prompt_characters(request));
  const int64_t completion = estimate_tokens(code_points(reply.content));
  reply.usage = {{"prompt_tokens", prompt}, {"completion_tokens", completion}, {"total_tokens", prompt + completion}};
  return reply;
}

std::unique_ptr<ReplyFileResponder> make_reply_file_responder(const ReplyFileResponderOptions& options) {
  std::vector<std::string> replies;
  for (const auto& path : options.files) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw std::invalid_argument("reply file " + path + ": cannot read (" + ec.message() + ")");
    if (size > kMaxReplyBytes) throw std::invalid_argument("reply file " + path + ": larger than 16 MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::invalid_argument("reply file " + path + ": cannot open");
    std::ostringstream text;
    text << in.rdbuf();
    replies.push_back(text.str());
    if (!is_utf8(replies.back())) throw std::invalid_argument("reply file " + path + ": not UTF-8 text");
  }
  for (const auto& t : options.texts) replies.push_back(t);
  return std::make_unique<ReplyFileResponder>(std::move(replies));
}

}  // namespace a3::agent::model_server
