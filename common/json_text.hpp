// The one way untrusted JSON text becomes a value (files, LLM replies, HTTP bodies, MCP
// messages, CAN tool arguments): bounded size and nesting depth, duplicate keys refused with
// their JSON path, invalid UTF-8 refused with its byte offset, and no recursion on the input's
// depth. Errors are one line: "<where>: <JSON path or byte offset>: <problem>".
// And the one way a value becomes text when it may hold bytes from outside (file names,
// model output): bytes that are not UTF-8 are replaced, never thrown about.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "common/json_file.hpp"  // InputError

namespace a3::common {

struct JsonLimits {
  std::size_t max_bytes = std::size_t{64} << 20;  // text longer than this is refused unread
  int max_depth = 128;                            // arrays/objects nested deeper are refused
};

// Parses `text`; throws InputError whose what() starts with `where`.
nlohmann::json parse_json_text(std::string_view text, const std::string& where, const JsonLimits& limits = {});
nlohmann::ordered_json parse_ordered_json_text(std::string_view text, const std::string& where,
                                               const JsonLimits& limits = {});
// The same without throwing: nullopt, and *error (if given) set to the one-line problem
// (without a `where` prefix).
std::optional<nlohmann::json> try_parse_json_text(std::string_view text, std::string* error = nullptr,
                                                  const JsonLimits& limits = {});

// j.dump(indent) with invalid UTF-8 in strings replaced by U+FFFD instead of throwing.
std::string dump_json_text(const nlohmann::json& j, int indent = -1);
std::string dump_json_text(const nlohmann::ordered_json& j, int indent = -1);

}  // namespace a3::common
