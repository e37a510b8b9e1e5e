// The table of message types (see message_registry.hpp).
#include "bridge/dronecan/message_registry.hpp"

#include <stdexcept>
#include <tuple>

#include "bridge/dronecan/dsdl_layout.hpp"
#include "bridge/dronecan/json_codec.hpp"
#include "bridge/dronecan/messages.hpp"

namespace a3::bridge {
namespace {

template <class Msg>
bool decode_to_json(const uint8_t* data, std::size_t size, nlohmann::json& out,
                    std::string& error) {
  Msg msg{};
  const CodecStatus status = decode_payload(data, size, msg);
  if (!status.ok()) {
    error = status.message(Msg::kType.full_name);
    return false;
  }
  out = message_to_json(msg);
  return true;
}

template <class Msg>
bool encode_from_json(const nlohmann::json& fields, Payload& out, std::string& error) {
  try {
    const Msg msg = message_from_json<Msg>(fields);
    const CodecStatus status = encode_payload(msg, out);
    if (!status.ok()) {
      error = status.message(Msg::kType.full_name);
      return false;
    }
    return true;
  } catch (const std::invalid_argument& e) {
    error = std::string(Msg::kType.full_name) + ": " + e.what();
    return false;
  }
}

template <class Msg>
MessageTypeEntry make_entry() {
  return MessageTypeEntry{Msg::kType,
                          &dsdl_layout::normalized_definition<Msg>,
                          &dsdl_layout::signature<Msg>,
                          &dsdl_layout::max_bit_length<Msg>,
                          &decode_to_json<Msg>,
                          &encode_from_json<Msg>};
}

template <class Tuple>
std::vector<MessageTypeEntry> make_entries() {
  return std::apply([](auto... msgs) { return std::vector<MessageTypeEntry>{
                        make_entry<decltype(msgs)>()...}; },
                    Tuple{});
}

}  // namespace

const std::vector<MessageTypeEntry>& message_types() {
  static const std::vector<MessageTypeEntry> entries = make_entries<MessageTypes>();
  return entries;
}

const std::vector<MessageTypeEntry>& nested_message_types() {
  static const std::vector<MessageTypeEntry> entries = make_entries<NestedTypes>();
  return entries;
}

const MessageTypeEntry* find_message_type(std::string_view name) {
  const MessageTypeEntry* by_short_name = nullptr;
  int short_matches = 0;
  for (const auto& entry : message_types()) {
    if (entry.info.full_name == name) return &entry;
    const std::string_view full = entry.info.full_name;
    const std::string_view short_name = full.substr(full.rfind('.') + 1);
    if (short_name == name) {
      by_short_name = &entry;
      ++short_matches;
    }
  }
  return short_matches == 1 ? by_short_name : nullptr;
}

const MessageTypeEntry* find_message_type(uint16_t data_type_id) {
  for (const auto& entry : message_types()) {
    if (entry.info.default_dtid == data_type_id) return &entry;
  }
  return nullptr;
}

void add_all_message_types(DataTypeTable& table) {
  for (const auto& entry : message_types()) {
    table.add(std::string(entry.info.full_name), TransferKind::kMessage, entry.info.default_dtid,
              entry.info.signature, (entry.info.max_bit_length + 7) / 8);
  }
}

}  // namespace a3::bridge
