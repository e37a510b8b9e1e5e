// Parsing a model's reply into one agent turn: intent, text and actions. Accepts a JSON object
// as the whole reply, inside ```json fences, or with prose around it (the outermost object is
// taken). Checks it: intent a non-empty string, text a string (may be absent), actions an
// array of MCP calls of known tools with arguments valid against the tool's schema, or A2A
// tasks known to the catalogue, sent to the task's peer, with a valid payload. Every problem
// names its place ("actions/2/args/z: ..."). Never throws on the model's output.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "agent/tool_catalog.hpp"

namespace a3::agent::llm {

struct ParsedReply {
  std::string intent;
  std::string text;
  // Normalised: {"type":"mcp","name","args"} / {"type":"a2a","task","to","payload"}.
  nlohmann::json actions = nlohmann::json::array();
  std::vector<std::string> problems;  // empty: the reply is usable
  bool ok() const { return problems.empty(); }
  std::string problems_text() const;  // joined with "; "
};

ParsedReply parse_reply(const std::string& content, const ToolCatalog& tools);

}  // namespace a3::agent::llm
