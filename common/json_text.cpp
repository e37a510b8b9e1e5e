// Bounded JSON parsing: nlohmann's SAX parser (iterative) feeding a DOM builder with an explicit
// stack, so neither parsing nor building recurses on the input's depth. Depth is bounded here,
// which is what makes nlohmann's recursive copy constructor and dump() safe on the result.
#include "common/json_text.hpp"

#include "common/json_pointer.hpp"

#include <string>
#include <type_traits>
#include <unordered_set>
#include <utility>
#include <vector>

namespace a3::common {
namespace {

// A refused input: where in it (JSON path or "byte N") and what is wrong.
struct JsonProblem {
  std::string location;
  std::string problem;
  std::string line() const { return location + ": " + problem; }
};


// Keeps the text of a key or value readable in a one-line message: invalid UTF-8 replaced,
// long text cut.
std::string quoted_for_message(const std::string& text) {
  constexpr std::size_t kMaxChars = 80;
  const std::string shown = text.size() > kMaxChars ? text.substr(0, kMaxChars) + "..." : text;
  return nlohmann::json(shown).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// nlohmann's parse errors read "[json.exception.parse_error.101] parse error at line 1,
// column 5: syntax error while parsing value - invalid literal; last read: 'x'"; keep the
// problem ("syntax error while parsing value - invalid literal") without the raw last token,
// which may hold the invalid bytes themselves.
std::string problem_of(const nlohmann::detail::exception& ex) {
  std::string text = ex.what();
  if (const auto colon = text.find(": "); text.rfind("[json.exception.parse_error", 0) == 0 && colon != std::string::npos) {
    text = text.substr(colon + 2);
  } else if (const auto bracket = text.find("] "); text.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) {
    text = text.substr(bracket + 2);
  }
  if (const auto last = text.find("; last read:"); last != std::string::npos) text.resize(last);
  if (text.find("ill-formed UTF-8 byte") != std::string::npos) return "invalid UTF-8 in a string";
  return "not valid JSON: " + text;
}

// One open array or object on the builder's stack.
template <typename Json>
struct OpenContainer {
  Json* value = nullptr;
  std::size_t next_index = 0;                // arrays: index of the next element
  std::string key;                           // objects: key of the next member
  std::unordered_set<std::string> keys_seen; // ordered objects only (their find is linear)
};

// SAX handler building the value; stops at the first problem.
template <typename Json>
class BoundedDomBuilder {
 public:
  using number_integer_t = typename Json::number_integer_t;
  using number_unsigned_t = typename Json::number_unsigned_t;
  using number_float_t = typename Json::number_float_t;
  using string_t = typename Json::string_t;
  using binary_t = typename Json::binary_t;

  explicit BoundedDomBuilder(int max_depth) : max_depth_(max_depth) {}

  Json& result() { return root_; }
  const std::optional<JsonProblem>& problem() const { return problem_; }

  bool null() { return add(Json(nullptr)); }
  bool boolean(bool v) { return add(Json(v)); }
  bool number_integer(number_integer_t v) { return add(Json(v)); }
  bool number_unsigned(number_unsigned_t v) { return add(Json(v)); }
  bool number_float(number_float_t v, const string_t&) { return add(Json(v)); }
  bool string(string_t& v) { return add(Json(std::move(v))); }
  bool binary(binary_t&) { return refuse(path_of_next(), "binary values are not JSON"); }

  bool start_object(std::size_t) { return open(Json::object()); }
  bool start_array(std::size_t) { return open(Json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(string_t& k) {
    OpenContainer<Json>& top = stack_.back();
    const bool duplicate = ordered() ? !top.keys_seen.insert(k).second : top.value->contains(k);
    if (duplicate) {
      return refuse(path_of_open(), "duplicate key " + quoted_for_message(k));
    }
    top.key = std::move(k);
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) {
    // nlohmann counts the offending byte as read; report its 0-based offset.
    const std::size_t offset = position > 0 ? position - 1 : 0;
    if (!problem_) problem_ = JsonProblem{"byte " + std::to_string(offset), problem_of(ex)};
    return false;
  }

 private:
  static constexpr bool ordered() { return std::is_same_v<Json, nlohmann::ordered_json>; }

  // Where the next value goes; nullptr for the root.
  Json* place(Json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    OpenContainer<Json>& top = stack_.back();
    if (top.value->is_array()) {
      ++top.next_index;
      top.value->push_back(std::move(v));
      return &top.value->back();
    }
    // Pointers to open containers stay valid: a parent only grows while its children are closed.
    return &((*top.value)[top.key] = std::move(v));
  }

  bool add(Json&& v) {
    place(std::move(v));
    return true;
  }

  bool open(Json&& empty) {
    if (static_cast<int>(stack_.size()) >= max_depth_) {
      return refuse(path_of_next(), "nested deeper than the limit of " + std::to_string(max_depth_) +
                                        " arrays/objects");
    }
    Json* opened = place(std::move(empty));
    stack_.emplace_back();
    stack_.back().value = opened;
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

  bool refuse(std::string location, std::string problem) {
    problem_ = JsonProblem{location.empty() ? "/" : std::move(location), std::move(problem)};
    return false;
  }

  // JSON pointer of the innermost open container.
  std::string path_of_open() const {
    std::string path;
    for (std::size_t i = 0; i + 1 < stack_.size(); ++i) path += "/" + token_of_open_child(stack_[i]);
    return path;
  }

  // JSON pointer of the value about to be added to the innermost open container.
  std::string path_of_next() const {
    if (stack_.empty()) return "";
    std::string path = path_of_open();
    const OpenContainer<Json>& top = stack_.back();
    return path + "/" + (top.value->is_array() ? std::to_string(top.next_index) : json_pointer_token(top.key));
  }

  // The token naming the open child of a container that is not the innermost: its last
  // element or current key.
  static std::string token_of_open_child(const OpenContainer<Json>& open) {
    if (open.value->is_array()) return std::to_string(open.next_index - 1);
    return json_pointer_token(open.key);
  }

  int max_depth_;
  Json root_;
  std::vector<OpenContainer<Json>> stack_;
  std::optional<JsonProblem> problem_;
};

template <typename Json>
std::optional<Json> parse_bounded(std::string_view text, const JsonLimits& limits, JsonProblem* problem) {
  if (text.size() > limits.max_bytes) {
    *problem = JsonProblem{"byte " + std::to_string(limits.max_bytes),
                           "text is " + std::to_string(text.size()) + " bytes, more than the limit of " +
                               std::to_string(limits.max_bytes)};
    return std::nullopt;
  }
  BoundedDomBuilder<Json> builder(limits.max_depth);
  const bool ok = Json::sax_parse(text.begin(), text.end(), &builder, nlohmann::json::input_format_t::json, true);
  if (!ok) {
    *problem = builder.problem().value_or(JsonProblem{"byte 0", "not valid JSON"});
    return std::nullopt;
  }
  return std::move(builder.result());
}

template <typename Json>
Json parse_or_throw(std::string_view text, const std::string& where, const JsonLimits& limits) {
  JsonProblem problem;
  auto value = parse_bounded<Json>(text, limits, &problem);
  if (!value) throw InputError(where + ": " + problem.line());
  return std::move(*value);
}

}  // namespace

nlohmann::json parse_json_text(std::string_view text, const std::string& where, const JsonLimits& limits) {
  return parse_or_throw<nlohmann::json>(text, where, limits);
}

nlohmann::ordered_json parse_ordered_json_text(std::string_view text, const std::string& where,
                                               const JsonLimits& limits) {
  return parse_or_throw<nlohmann::ordered_json>(text, where, limits);
}

std::optional<nlohmann::json> try_parse_json_text(std::string_view text, std::string* error,
                                                  const JsonLimits& limits) {
  JsonProblem problem;
  auto value = parse_bounded<nlohmann::json>(text, limits, &problem);
  if (!value && error) *error = problem.line();
  return value;
}

std::string dump_json_text(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string dump_json_text(const nlohmann::ordered_json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

std::string json_pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

}  // namespace a3::common
