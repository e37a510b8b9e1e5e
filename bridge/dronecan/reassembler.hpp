// Turns received DroneCAN frames back into transfers: checks every tail byte (start, end,
// toggle, transfer ID), frame lengths and the transfer CRC, and rejects and counts what is
// wrong. Memory is bounded (a fixed table of sessions, each at most the type's maximum
// payload, allocated once) and so is time: a transfer whose next frame does not come within
// the timeout is dropped. Time comes only from the caller (frame receive times, expire()).
// Not thread-safe: one reassembler per receiving thread.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "bridge/can/can_frame.hpp"
#include "bridge/dronecan/data_type_table.hpp"
#include "bridge/dronecan/transfer.hpp"

namespace a3::bridge {

// Why a frame was rejected.
enum class FrameError : uint8_t {
  kNotDroneCan,            // standard (11-bit) ID, remote or error frame
  kEmpty,                  // no data, so no tail byte
  kTooLongForType,         // more payload than the data type allows
  kShortFrame,             // a frame before the last of a multi-frame transfer with < 8 bytes
  kAnonymousMultiFrame,    // anonymous transfers must fit one frame
  kMissedStart,            // a continuation with no transfer in progress
  kUnexpectedTransferId,   // a continuation with another transfer ID than the one in progress
  kToggleError,            // toggle bit out of sequence (a frame lost or repeated)
  kBadCrc,                 // the transfer CRC does not match
  kSessionTableFull,       // too many transfers in progress at once
  kCount
};
std::string_view to_string(FrameError error);

struct ReassemblerConfig {
  std::size_t max_sessions = 32;           // transfers in progress at once
  int64_t transfer_timeout_us = 2'000'000;  // max gap between frames of one transfer (UAVCAN v0: 2 s)
  uint8_t local_node_id = 0;               // services for other nodes are ignored; 0: accept all
};

struct ReassemblerStats {
  uint64_t frames = 0;               // every frame given to accept()
  uint64_t single_frame_transfers = 0;
  uint64_t multi_frame_transfers = 0;
  uint64_t ignored_frames = 0;       // unknown data type, or a service for another node
  uint64_t expired_transfers = 0;    // dropped: the next frame never came (timeout)
  uint64_t interrupted_transfers = 0;  // dropped: the same source started another transfer
  std::array<uint64_t, static_cast<std::size_t>(FrameError::kCount)> rejected{};

  uint64_t transfers() const { return single_frame_transfers + multi_frame_transfers; }
  uint64_t rejected_frames() const;
  uint64_t rejected_count(FrameError error) const {
    return rejected[static_cast<std::size_t>(error)];
  }
};

struct ReceivedTransfer {
  TransferHeader header;
  int64_t timestamp_us = 0;     // receive time of its first frame
  const DataTypeTable::Entry* type = nullptr;
  const uint8_t* payload = nullptr;  // valid until the next call to accept()
  std::size_t size = 0;
};

enum class FrameVerdict : uint8_t {
  kTransferComplete,  // `out` holds a transfer
  kInProgress,        // part of a multi-frame transfer
  kIgnored,           // not for this receiver (unknown type, another node's service)
  kRejected,          // bad frame; see last_error() and stats()
};

class TransferReassembler {
 public:
  // `types` must outlive the reassembler (types may be added later).
  explicit TransferReassembler(const DataTypeTable& types, ReassemblerConfig config = {});

  FrameVerdict accept(const CanFrame& frame, int64_t rx_time_us, ReceivedTransfer& out);
  // Drops transfers whose last frame came more than the timeout before now_us.
  void expire(int64_t now_us);

  const ReassemblerStats& stats() const { return stats_; }
  FrameError last_error() const { return last_error_; }
  std::size_t active_transfers() const;
  const ReassemblerConfig& config() const { return config_; }

 private:
  struct Session {
    uint32_t key = 0;  // the CAN ID without its priority
    TransferHeader header;
    const DataTypeTable::Entry* type = nullptr;
    uint8_t transfer_id = 0;
    bool next_toggle = false;
    uint16_t expected_crc = 0;
    int64_t start_us = 0;
    int64_t last_us = 0;
    std::size_t size = 0;
    std::array<uint8_t, kMaxTransferPayloadBytes> buffer{};
  };

  FrameVerdict reject(FrameError error);
  Session* find_session(uint32_t key);
  // A free session, now active (expiring stale ones if none is free), or null.
  Session* allocate_session(int64_t now_us);
  void drop(Session& session);
  const DataTypeTable::Entry* find_type(TransferKind kind, uint16_t data_type_id);

  const DataTypeTable& types_;
  ReassemblerConfig config_;
  std::vector<Session> sessions_;
  // The indices of the active sessions (few: a frame looks only at these) and of the free ones.
  std::vector<uint32_t> active_;
  std::vector<uint32_t> free_;
  // The type found last: a transfer's frames come one after another. Entries never move.
  uint32_t last_type_key_ = UINT32_MAX;
  const DataTypeTable::Entry* last_type_ = nullptr;
  ReassemblerStats stats_;
  FrameError last_error_ = FrameError::kCount;
  std::array<uint8_t, kMaxTransferPayloadBytes> completed_{};
};

}  // namespace a3::bridge
