// Balanced-brace scanning with JSON string rules.
#include "agent/llm/json_extract.hpp"

namespace a3::agent::llm {
namespace {

// nlohmann's message without its "[json.exception.parse_error.101] " tag.
std::string plain_message(const std::exception& e) {
  std::string m = e.what();
  if (!m.empty() && m.front() == '[') {
    const auto close = m.find("] ");
    if (close != std::string::npos) m = m.substr(close + 2);
  }
  return m;
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
      out += '?';
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
  auto whole = nlohmann::json::parse(text, nullptr, false);
  if (!whole.is_discarded() && whole.is_object()) {
    out.object = std::move(whole);
    return out;
  }
  const auto spans = top_level_object_spans(text);
  if (spans.empty()) {
    out.error = whole.is_discarded() ? "no JSON object in the reply (no '{' found)"
                                     : std::string("the reply is JSON but a ") + whole.type_name() + ", not an object";
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
    try {
      auto j = nlohmann::json::parse(text.begin() + static_cast<std::ptrdiff_t>(s.begin),
                                     text.begin() + static_cast<std::ptrdiff_t>(s.end));
      if (j.is_object()) {
        out.object = std::move(j);
        return out;
      }
    } catch (const nlohmann::json::parse_error& e) {
      if (first_error.empty()) {
        first_error = "the JSON object starting at character " + std::to_string(s.begin) +
                      " is not valid JSON: " + plain_message(e);
      }
    }
  }
  out.error = first_error;
  return out;
}

}  // namespace a3::agent::llm
