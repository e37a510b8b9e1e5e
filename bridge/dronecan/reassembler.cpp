// DroneCAN transfer reassembly (see reassembler.hpp).
#include "bridge/dronecan/reassembler.hpp"

#include <algorithm>
#include <stdexcept>

#include "bridge/dronecan/crc.hpp"

namespace a3::bridge {

std::string_view to_string(FrameError error) {
  switch (error) {
    case FrameError::kNotDroneCan: return "not a DroneCAN frame (standard ID, remote or error frame)";
    case FrameError::kEmpty: return "empty frame (no tail byte)";
    case FrameError::kTooLongForType: return "transfer longer than its data type allows";
    case FrameError::kShortFrame: return "frame shorter than 8 bytes before the end of a transfer";
    case FrameError::kAnonymousMultiFrame: return "anonymous multi-frame transfer";
    case FrameError::kMissedStart: return "continuation frame without a transfer in progress";
    case FrameError::kUnexpectedTransferId: return "unexpected transfer ID";
    case FrameError::kToggleError: return "toggle bit out of sequence";
    case FrameError::kBadCrc: return "transfer CRC mismatch";
    case FrameError::kSessionTableFull: return "too many transfers in progress";
    case FrameError::kCount: break;
  }
  return "no error";
}

uint64_t ReassemblerStats::rejected_frames() const {
  uint64_t total = 0;
  for (const uint64_t count : rejected) total += count;
  return total;
}

TransferReassembler::TransferReassembler(const DataTypeTable& types, ReassemblerConfig config)
    : types_(types), config_(config) {
  if (config_.max_sessions == 0) {
    throw std::invalid_argument("TransferReassembler: max_sessions must be at least 1");
  }
  if (config_.transfer_timeout_us <= 0) {
    throw std::invalid_argument("TransferReassembler: transfer_timeout_us must be positive, not " +
                                std::to_string(config_.transfer_timeout_us));
  }
  sessions_.resize(config_.max_sessions);
  active_.reserve(config_.max_sessions);
  for (std::size_t i = config_.max_sessions; i-- > 0;) free_.push_back(static_cast<uint32_t>(i));
}

FrameVerdict TransferReassembler::reject(FrameError error) {
  ++stats_.rejected[static_cast<std::size_t>(error)];
  last_error_ = error;
  return FrameVerdict::kRejected;
}

TransferReassembler::Session* TransferReassembler::find_session(uint32_t key) {
  for (const uint32_t index : active_) {
    if (sessions_[index].key == key) return &sessions_[index];
  }
  return nullptr;
}

TransferReassembler::Session* TransferReassembler::allocate_session(int64_t now_us) {
  if (free_.empty()) expire(now_us);
  if (free_.empty()) return nullptr;
  const uint32_t index = free_.back();
  free_.pop_back();
  active_.push_back(index);
  return &sessions_[index];
}

void TransferReassembler::drop(Session& session) {
  const auto index = static_cast<uint32_t>(&session - sessions_.data());
  active_.erase(std::find(active_.begin(), active_.end(), index));
  free_.push_back(index);
}

const DataTypeTable::Entry* TransferReassembler::find_type(TransferKind kind, uint16_t data_type_id) {
  const uint32_t key = (static_cast<uint32_t>(kind) << 16) | data_type_id;
  if (key == last_type_key_) return last_type_;
  const DataTypeTable::Entry* type = types_.find(kind, data_type_id);
  if (type != nullptr) {  // an unknown type may be added later: only hits are remembered
    last_type_key_ = key;
    last_type_ = type;
  }
  return type;
}

std::size_t TransferReassembler::active_transfers() const { return active_.size(); }

void TransferReassembler::expire(int64_t now_us) {
  for (std::size_t i = active_.size(); i-- > 0;) {
    Session& s = sessions_[active_[i]];
    if (now_us - s.last_us > config_.transfer_timeout_us) {
      drop(s);
      ++stats_.expired_transfers;
    }
  }
}

FrameVerdict TransferReassembler::accept(const CanFrame& frame, int64_t rx_time_us,
                                         ReceivedTransfer& out) {
  ++stats_.frames;
  if (!frame.extended || frame.remote || frame.error) return reject(FrameError::kNotDroneCan);
  if (frame.size == 0) return reject(FrameError::kEmpty);
  const std::size_t frame_size = std::min<std::size_t>(frame.size, 8);

  bool anonymous = false;
  TransferHeader header = parse_can_id(frame.id, &anonymous);
  const TailByte tail = TailByte::parse(frame.data[frame_size - 1]);
  header.transfer_id = tail.transfer_id;
  if (header.kind != TransferKind::kMessage && config_.local_node_id != 0 &&
      header.destination_node_id != config_.local_node_id) {
    ++stats_.ignored_frames;
    return FrameVerdict::kIgnored;
  }
  const DataTypeTable::Entry* type =
      anonymous ? nullptr : find_type(header.kind, header.data_type_id);
  if (type == nullptr && !anonymous) {
    ++stats_.ignored_frames;
    return FrameVerdict::kIgnored;
  }
  const uint32_t key = frame.id & 0x00FFFFFFu;
  const std::size_t data_size = frame_size - 1;

  if (tail.start_of_transfer && tail.end_of_transfer) {
    if (tail.toggle) return reject(FrameError::kToggleError);
    if (Session* previous = find_session(key); previous != nullptr) {
      drop(*previous);
      ++stats_.interrupted_transfers;
    }
    if (anonymous) {
      // Only the two low bits of the type ID travel; the receiver cannot check the type.
      type = nullptr;
    } else if (data_size > type->max_payload_bytes) {
      return reject(FrameError::kTooLongForType);
    }
    std::copy(frame.data.begin(), frame.data.begin() + static_cast<std::ptrdiff_t>(data_size),
              completed_.begin());
    out = ReceivedTransfer{header, rx_time_us, type, completed_.data(), data_size};
    ++stats_.single_frame_transfers;
    return FrameVerdict::kTransferComplete;
  }

  if (tail.start_of_transfer) {
    if (anonymous) return reject(FrameError::kAnonymousMultiFrame);
    if (frame_size != 8) return reject(FrameError::kShortFrame);
    if (tail.toggle) return reject(FrameError::kToggleError);
    Session* session = find_session(key);
    if (session != nullptr) {
      ++stats_.interrupted_transfers;
    } else {
      session = allocate_session(rx_time_us);
      if (session == nullptr) return reject(FrameError::kSessionTableFull);
    }
    session->key = key;
    session->header = header;
    session->type = type;
    session->transfer_id = tail.transfer_id;
    session->next_toggle = true;
    session->expected_crc = static_cast<uint16_t>(frame.data[0] | (frame.data[1] << 8));
    session->start_us = rx_time_us;
    session->last_us = rx_time_us;
    session->size = data_size - 2;
    std::copy(frame.data.begin() + 2, frame.data.begin() + 7, session->buffer.begin());
    if (session->size > type->max_payload_bytes) {
      drop(*session);
      return reject(FrameError::kTooLongForType);
    }
    return FrameVerdict::kInProgress;
  }

  Session* session = find_session(key);
  if (session != nullptr && rx_time_us - session->last_us > config_.transfer_timeout_us) {
    drop(*session);
    ++stats_.expired_transfers;
    session = nullptr;
  }
  if (session == nullptr) return reject(FrameError::kMissedStart);
  // Frames of another transfer under the same ID (e.g. a node ID conflict) are rejected
  // without disturbing the one in progress.
  if (tail.transfer_id != session->transfer_id) return reject(FrameError::kUnexpectedTransferId);
  if (tail.toggle != session->next_toggle) {
    drop(*session);
    return reject(FrameError::kToggleError);
  }
  if (!tail.end_of_transfer && frame_size != 8) {
    drop(*session);
    return reject(FrameError::kShortFrame);
  }
  if (session->size + data_size > type->max_payload_bytes) {
    drop(*session);
    return reject(FrameError::kTooLongForType);
  }
  std::copy(frame.data.begin(), frame.data.begin() + static_cast<std::ptrdiff_t>(data_size),
            session->buffer.begin() + static_cast<std::ptrdiff_t>(session->size));
  session->size += data_size;
  session->last_us = rx_time_us;
  session->next_toggle = !session->next_toggle;
  if (!tail.end_of_transfer) return FrameVerdict::kInProgress;

  drop(*session);
  const uint16_t crc = crc16_ccitt_false(session->buffer.data(), session->size, type->crc_seed);
  if (crc != session->expected_crc) return reject(FrameError::kBadCrc);
  std::copy(session->buffer.begin(),
            session->buffer.begin() + static_cast<std::ptrdiff_t>(session->size),
            completed_.begin());
  out = ReceivedTransfer{session->header, session->start_us, type, completed_.data(),
                         session->size};
  ++stats_.multi_frame_transfers;
  return FrameVerdict::kTransferComplete;
}

}  // namespace a3::bridge
