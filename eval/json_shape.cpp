// Depth and duplicate-key checks with an explicit stack; paths are built only for violations.
#include "eval/json_shape.hpp"

#include "common/json_pointer.hpp"
#include "eval/key_bucket.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

namespace a3::eval {
namespace {

std::string_view name_of(const rapidjson::Value::Member& m) {
  return {m.name.GetString(), m.name.GetStringLength()};
}

// Below this many members, comparing every pair is cheaper than sorting.
constexpr std::size_t kPairwiseMembers = 24;

}  // namespace

bool JsonShapeChecker::check(const rapidjson::Value& root, Violations& out) {
  const std::size_t before = out.size();
  stack_.clear();
  if (root.IsObject()) check_keys(root, out);
  if (root.IsObject() || root.IsArray()) stack_.push_back({&root, 0});
  while (!stack_.empty()) {
    Frame& top = stack_.back();
    const rapidjson::Value* child = nullptr;
    if (top.container->IsArray()) {
      if (top.next < top.container->Size()) child = &(*top.container)[top.next];
    } else if (top.next < top.container->MemberCount()) {
      child = &(top.container->MemberBegin() + top.next)->value;
    }
    if (child == nullptr) {
      stack_.pop_back();
      continue;
    }
    ++top.next;
    if (!child->IsObject() && !child->IsArray()) continue;
    if (static_cast<int>(stack_.size()) >= max_depth_) {
      out.push_back({current_path(), "json-depth",
                     "arrays/objects nested deeper than the limit of " + std::to_string(max_depth_)});
      return true;  // nothing below is looked into
    }
    if (child->IsObject()) check_keys(*child, out);
    stack_.push_back({child, 0});
  }
  return out.size() > before;
}

void JsonShapeChecker::check_keys(const rapidjson::Value& object, Violations& out) {
  const rapidjson::SizeType n = object.MemberCount();
  if (n < 2) return;
  keys_.clear();
  for (auto m = object.MemberBegin(); m != object.MemberEnd(); ++m) keys_.push_back(name_of(*m));
  repeated_.clear();
  if (!find_repeated_keys(keys_.data(), keys_.size(), &repeated_)) return;
  // stack_ holds the object's ancestors, each at the child leading to it.
  for (const std::string_view key : repeated_) {
    out.push_back({current_path(), "json-duplicate-key",
                   "duplicate key \"" + std::string(key) + "\" (readers disagree on which value counts)"});
  }
}

bool find_repeated_keys(std::string_view* keys, std::size_t count,
                        std::vector<std::string_view>* repeated) {
  if (count < 2) return false;
  bool found = false;
  // Each repeated key once (stopping at the first when nobody wants the list).
  auto report = [&](std::string_view key) {
    found = true;
    if (repeated != nullptr) repeated->push_back(key);
    return repeated == nullptr;
  };
  if (count > kPairwiseMembers) {
    std::sort(keys, keys + count);
    for (std::size_t i = 1; i < count; ++i) {
      if (keys[i] == keys[i - 1] && (i < 2 || keys[i - 2] != keys[i]) && report(keys[i])) break;
    }
    return found;
  }
  // Length and first byte settle almost every pair without comparing the keys' bytes.
  const auto same = [](std::string_view a, std::string_view b) {
    return a.size() == b.size() && (a.empty() || (a[0] == b[0] && a == b));
  };
  // A key can only repeat an earlier one in the same bucket (key_bucket.hpp).
  uint64_t seen = key_bucket_bit(keys[0]);
  for (std::size_t i = 1; i < count; ++i) {
    const uint64_t bit = key_bucket_bit(keys[i]);
    const bool maybe_repeated = (seen & bit) != 0;
    seen |= bit;
    if (!maybe_repeated) continue;
    for (std::size_t j = 0; j < i; ++j) {
      if (!same(keys[i], keys[j])) continue;
      // Each key once: at its second occurrence (j is the first; none between j and i).
      bool earlier = false;
      for (std::size_t k = j + 1; k < i && !earlier; ++k) earlier = same(keys[k], keys[i]);
      if (!earlier && report(keys[i])) return true;
      break;
    }
  }
  return found;
}

// Each frame names the child it last stepped into (next - 1).
std::string JsonShapeChecker::current_path() const {
  std::string path;
  for (const Frame& f : stack_) {
    const rapidjson::SizeType index = f.next - 1;
    if (f.container->IsArray()) {
      path += "/" + std::to_string(index);
    } else {
      path += "/" + common::json_pointer_token(name_of(*(f.container->MemberBegin() + index)));
    }
  }
  return path;
}

}  // namespace a3::eval
