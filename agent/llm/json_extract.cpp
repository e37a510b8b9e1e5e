// Balanced-brace scanning with JSON string rules.
#include "agent/llm/json_extract.hpp"

#include "common/json_text.hpp"

namespace a3::agent::llm {
namespace {

// try_parse_json_text's problem about text[begin...] with its byte offset made one into `text`:
// "byte 7: not valid JSON: ..." of a span at 12 becomes "byte 19: not valid JSON: ...".
std::string problem_in_text(const std::string& span_problem, std::size_t begin) {
  if (span_problem.rfind("byte ", 0) != 0) return span_problem;
  std::size_t digits = 0;
  const std::size_t offset = std::stoul(span_problem.substr(5), &digits);
  return "byte " + std::to_string(begin + offset) + span_problem.substr(5 + digits);
}

// Length of the well-formed UTF-8 sequence starting at text[i], 0 when it is not one.
std::size_t utf8_sequence_length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned char lo = 0x80, hi = 0xBF;  // the allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;  // no surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return n;
}

}  // namespace

std::string valid_utf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence_length(text, i);
    if (n == 0) {
      out += "\xEF\xBF\xBD";  // U+FFFD REPLACEMENT CHARACTER
      ++i;
    } else {
      out.append(text, i, n);
      i += n;
    }
  }
  return out;
}

std::vector<TextSpan> top_level_object_spans(const std::string& text) {
  std::vector<TextSpan> spans;
  std::size_t depth = 0, begin = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (depth == 0) {
      if (c == '{') {
        depth = 1;
        begin = i;
        in_string = escaped = false;
      }
      continue;
    }
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '{') {
      ++depth;
    } else if (c == '}' && --depth == 0) {
      spans.push_back({begin, i + 1, true});
    }
  }
  if (depth > 0) spans.push_back({begin, text.size() + 1, false});
  return spans;
}

ExtractedObject extract_json_object(const std::string& text) {
  ExtractedObject out;
  std::string whole_problem;
  auto whole = common::try_parse_json_text(text, &whole_problem);
  if (whole && whole->is_object()) {
    out.object = std::move(*whole);
    return out;
  }
  const auto spans = top_level_object_spans(text);
  if (spans.empty()) {
    out.error = !whole ? "no JSON object in the reply (no '{' found)"
                       : std::string("the reply is JSON but a ") + whole->type_name() + ", not an object";
    return out;
  }
  std::string first_error;
  for (const auto& s : spans) {
    if (!s.closed) {
      if (first_error.empty()) {
        first_error = "the JSON object starting at character " + std::to_string(s.begin) +
                      " is never closed (reply cut off?)";
      }
      continue;
    }
    std::string problem;
    auto j = common::try_parse_json_text(std::string_view(text).substr(s.begin, s.end - s.begin), &problem);
    if (j && j->is_object()) {
      out.object = std::move(*j);
      return out;
    }
    if (!j && first_error.empty()) {
      first_error = "the JSON object starting at character " + std::to_string(s.begin) + ": " +
                    problem_in_text(problem, s.begin);
    }
  }
  out.error = first_error;
  return out;
}

}  // namespace a3::agent::llm
