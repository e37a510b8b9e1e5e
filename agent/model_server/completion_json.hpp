// The JSON `a3rig serve-model` answers with: a `chat.completion` object, or for `stream: true`
// the sequence of `chat.completion.chunk` objects sent as server-sent events. Chunks per choice
// (choice after choice): the role delta {"role":"assistant","content":""}; the content in
// pieces of about kPieceBytes (at UTF-8 boundaries, at most kMaxPieces); each tool call as a
// delta {index, id, type, function:{name, arguments:""}} then its arguments in pieces; a last
// chunk with an empty delta and the finish_reason. With include_usage, one more chunk with
// `choices: []` and the usage.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "agent/model_server/model_responder.hpp"

namespace a3::agent::model_server {

struct CompletionHeader {
  std::string id;  // "chatcmpl-a3rig-<n>"
  int64_t created = 0;
  std::string model;
};

constexpr std::size_t kPieceBytes = 16;
constexpr std::size_t kMaxPieces = 64;

// The assistant message of one choice: content null when it is empty and there are tool calls.
nlohmann::json message_json(const ResponderReply& reply);
nlohmann::json completion_json(const CompletionHeader& header, const std::vector<ResponderReply>& choices,
                               const nlohmann::json& usage);
// `usage` null: no usage chunk.
std::vector<nlohmann::json> completion_chunks(const CompletionHeader& header, const std::vector<ResponderReply>& choices,
                                              const nlohmann::json& usage);
// `text` cut into pieces of about kPieceBytes without splitting a UTF-8 character.
std::vector<std::string> text_pieces(const std::string& text);

}  // namespace a3::agent::model_server
