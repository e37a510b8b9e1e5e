// The reassembler rejects and counts bad frames (wrong length, bad CRC, toggle errors,
// interleaved transfers under one node ID, transfers that never end), keeps transfers from
// different nodes apart, and stays bounded in memory and time.
#include <gtest/gtest.h>

#include <vector>

#include "bridge/dronecan/messages.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "bridge/dronecan/transfer.hpp"

namespace a3::bridge {
namespace {

class ReassemblerTest : public ::testing::Test {
 protected:
  ReassemblerTest() {
    table_.add_message<AhrsRawImu>();
    table_.add_message<NodeStatus>();
    table_.add_message<EscStatus>();
  }

  // A 9-frame RawIMU transfer from `node` with transfer ID `tid` and a recognisable payload.
  std::vector<CanFrame> imu_frames(uint8_t node, uint8_t tid, float marker) {
    AhrsRawImu imu;
    imu.timestamp.usec = node;
    imu.integration_interval = marker;
    imu.covariance = {1, 2, 3, 4, 5, 6};
    Payload payload;
    std::vector<CanFrame> frames;
    EXPECT_TRUE(append_message_frames(imu, message_header<AhrsRawImu>(node, tid), payload, frames).ok());
    return frames;
  }

  // The one frame of an ArmingStatus from node 3, a type the fixture's table does not list
  // (at() throws, failing the test, if it could not be encoded).
  CanFrame arming_frame() {
    Payload payload;
    std::vector<CanFrame> frames;
    EXPECT_TRUE(append_message_frames(ArmingStatus{255}, message_header<ArmingStatus>(3, 0), payload, frames).ok());
    return frames.at(0);
  }

  AhrsRawImu decode_imu(const ReceivedTransfer& t) {
    AhrsRawImu imu;
    EXPECT_TRUE(decode_payload(t.payload, t.size, imu).ok());
    return imu;
  }

  // Feeds frames 1 ms apart from t0; returns the completed transfers' markers.
  std::vector<float> feed(TransferReassembler& r, const std::vector<CanFrame>& frames,
                          int64_t t0_us = 0) {
    std::vector<float> markers;
    ReceivedTransfer transfer;
    int64_t t = t0_us;
    for (const auto& frame : frames) {
      if (r.accept(frame, t, transfer) == FrameVerdict::kTransferComplete) {
        markers.push_back(decode_imu(transfer).integration_interval);
      }
      t += 1000;
    }
    return markers;
  }

  DataTypeTable table_;
};

TEST_F(ReassemblerTest, AGoodTransferCompletesOnItsLastFrame) {
  TransferReassembler r(table_);
  const auto frames = imu_frames(10, 3, 0.5f);
  ASSERT_EQ(frames.size(), 9u);
  EXPECT_EQ(feed(r, frames), std::vector<float>{0.5f});
  EXPECT_EQ(r.stats().multi_frame_transfers, 1u);
  EXPECT_EQ(r.stats().rejected_frames(), 0u);
  EXPECT_EQ(r.active_transfers(), 0u);
}

TEST_F(ReassemblerTest, BadCrcIsRejected) {
  TransferReassembler r(table_);
  auto frames = imu_frames(10, 3, 0.5f);
  frames[3].data[2] ^= 0x01;  // one payload bit flipped on the wire
  EXPECT_TRUE(feed(r, frames).empty());
  EXPECT_EQ(r.stats().rejected_count(FrameError::kBadCrc), 1u);
  EXPECT_EQ(r.active_transfers(), 0u);
}

TEST_F(ReassemblerTest, ALostFrameIsAToggleError) {
  TransferReassembler r(table_);
  auto frames = imu_frames(10, 3, 0.5f);
  frames.erase(frames.begin() + 2);
  EXPECT_TRUE(feed(r, frames).empty());
  EXPECT_EQ(r.stats().rejected_count(FrameError::kToggleError), 1u);
  // The rest of the transfer has nothing to attach to.
  EXPECT_EQ(r.stats().rejected_count(FrameError::kMissedStart), frames.size() - 3);
}

TEST_F(ReassemblerTest, ARepeatedFrameIsAToggleError) {
  TransferReassembler r(table_);
  auto frames = imu_frames(10, 3, 0.5f);
  frames.insert(frames.begin() + 2, frames[1]);
  EXPECT_TRUE(feed(r, frames).empty());
  EXPECT_EQ(r.stats().rejected_count(FrameError::kToggleError), 1u);
}

TEST_F(ReassemblerTest, WrongLengthsAreRejected) {
  TransferReassembler r(table_);
  auto frames = imu_frames(10, 3, 0.5f);
  auto short_middle = frames;
  short_middle[2].size = 6;
  short_middle[2].data[5] = frames[2].data[7];  // tail byte moved to the end
  EXPECT_TRUE(feed(r, short_middle).empty());
  EXPECT_EQ(r.stats().rejected_count(FrameError::kShortFrame), 1u);

  auto short_first = frames;
  short_first[0].size = 5;
  short_first[0].data[4] = frames[0].data[7];
  EXPECT_TRUE(feed(r, short_first).empty());
  EXPECT_EQ(r.stats().rejected_count(FrameError::kShortFrame), 2u);

  CanFrame empty = frames[0];
  empty.size = 0;
  ReceivedTransfer t;
  EXPECT_EQ(r.accept(empty, 0, t), FrameVerdict::kRejected);
  EXPECT_EQ(r.last_error(), FrameError::kEmpty);

  CanFrame standard = frames[0];
  standard.extended = false;
  standard.id = 0x123;
  EXPECT_EQ(r.accept(standard, 0, t), FrameVerdict::kRejected);
  EXPECT_EQ(r.last_error(), FrameError::kNotDroneCan);
}

TEST_F(ReassemblerTest, ATransferLongerThanItsTypeIsRejected) {
  // A NodeStatus (at most 7 bytes) sent as a 3-frame transfer of 16 bytes.
  TransferReassembler r(table_);
  std::vector<uint8_t> payload(16, 0xAB);
  std::vector<CanFrame> frames;
  append_transfer_frames(message_header<NodeStatus>(5, 0), NodeStatus::kType.signature,
                         payload.data(), payload.size(), frames);
  ReceivedTransfer t;
  for (const auto& f : frames) EXPECT_NE(r.accept(f, 0, t), FrameVerdict::kTransferComplete);
  EXPECT_EQ(r.stats().rejected_count(FrameError::kTooLongForType), 1u);
}

TEST_F(ReassemblerTest, InterleavedTransfersFromTwoNodesBothArrive) {
  // On a real bus two nodes' frames interleave by arbitration: each is its own session.
  TransferReassembler r(table_);
  const auto a = imu_frames(10, 1, 0.25f);
  const auto b = imu_frames(11, 1, 0.75f);
  std::vector<CanFrame> mixed;
  for (std::size_t i = 0; i < a.size(); ++i) {
    mixed.push_back(a[i]);
    mixed.push_back(b[i]);
  }
  EXPECT_EQ(feed(r, mixed), (std::vector<float>{0.25f, 0.75f}));
  EXPECT_EQ(r.stats().rejected_frames(), 0u);
}

TEST_F(ReassemblerTest, InterleavedTransfersUnderOneNodeIdAreRejectedNotMixed) {
  // Two nodes that both claim node ID 10 (a conflict): their frames share a CAN ID.
  TransferReassembler r(table_);
  const auto a = imu_frames(10, 4, 0.25f);
  const auto b = imu_frames(10, 9, 0.75f);
  std::vector<CanFrame> mixed;
  for (std::size_t i = 0; i < a.size(); ++i) {
    mixed.push_back(a[i]);
    mixed.push_back(b[i]);
  }
  // b's start interrupts a; a's later frames carry the wrong transfer ID; b completes whole.
  EXPECT_EQ(feed(r, mixed), std::vector<float>{0.75f});
  EXPECT_EQ(r.stats().interrupted_transfers, 1u);
  EXPECT_EQ(r.stats().rejected_count(FrameError::kUnexpectedTransferId), a.size() - 1);
}

TEST_F(ReassemblerTest, ATransferThatNeverEndsExpires) {
  ReassemblerConfig config;
  config.transfer_timeout_us = 100'000;
  TransferReassembler r(table_, config);
  auto frames = imu_frames(10, 3, 0.5f);
  const CanFrame last = frames.back();
  frames.pop_back();
  EXPECT_TRUE(feed(r, frames, 0).empty());
  EXPECT_EQ(r.active_transfers(), 1u);
  r.expire(50'000);
  EXPECT_EQ(r.active_transfers(), 1u) << "not yet stale";
  r.expire(7'000 + 100'001);  // the last frame came at 7 ms
  EXPECT_EQ(r.active_transfers(), 0u);
  EXPECT_EQ(r.stats().expired_transfers, 1u);
  ReceivedTransfer t;
  EXPECT_EQ(r.accept(last, 200'000, t), FrameVerdict::kRejected);
  EXPECT_EQ(r.last_error(), FrameError::kMissedStart);
}

TEST_F(ReassemblerTest, ALateContinuationExpiresItsTransferWithoutAnExpireCall) {
  ReassemblerConfig config;
  config.transfer_timeout_us = 100'000;
  TransferReassembler r(table_, config);
  const auto frames = imu_frames(10, 3, 0.5f);
  ReceivedTransfer t;
  EXPECT_EQ(r.accept(frames[0], 0, t), FrameVerdict::kInProgress);
  EXPECT_EQ(r.accept(frames[1], 500'000, t), FrameVerdict::kRejected);
  EXPECT_EQ(r.stats().expired_transfers, 1u);
}

TEST_F(ReassemblerTest, SessionTableIsBounded) {
  ReassemblerConfig config;
  config.max_sessions = 4;
  config.transfer_timeout_us = 100'000;
  TransferReassembler r(table_, config);
  ReceivedTransfer t;
  for (uint8_t node = 1; node <= 4; ++node) {
    EXPECT_EQ(r.accept(imu_frames(node, 0, 1.0f)[0], 0, t), FrameVerdict::kInProgress);
  }
  EXPECT_EQ(r.accept(imu_frames(5, 0, 1.0f)[0], 1000, t), FrameVerdict::kRejected);
  EXPECT_EQ(r.last_error(), FrameError::kSessionTableFull);
  // Once the stale ones have expired, a new transfer finds room.
  EXPECT_EQ(r.accept(imu_frames(5, 0, 1.0f)[0], 200'000, t), FrameVerdict::kInProgress);
  EXPECT_EQ(r.stats().expired_transfers, 4u);
  EXPECT_EQ(r.active_transfers(), 1u);
}

TEST_F(ReassemblerTest, UnknownTypesAreIgnoredAndSingleFramesNeedToggleZero) {
  TransferReassembler r(table_);
  ReceivedTransfer t;
  EXPECT_EQ(r.accept(arming_frame(), 0, t), FrameVerdict::kIgnored);
  EXPECT_EQ(r.stats().ignored_frames, 1u);

  Payload payload;
  std::vector<CanFrame> frames;
  ASSERT_TRUE(append_message_frames(NodeStatus{}, message_header<NodeStatus>(3, 31), payload,
                                    frames).ok());
  EXPECT_EQ(r.accept(frames[0], 0, t), FrameVerdict::kTransferComplete);
  EXPECT_EQ(t.header.transfer_id, 31);
  frames[0].data[frames[0].size - 1] |= 0x20;  // toggle set on a single-frame transfer
  EXPECT_EQ(r.accept(frames[0], 0, t), FrameVerdict::kRejected);
  EXPECT_EQ(r.last_error(), FrameError::kToggleError);
}

// A receiver learns a type after frames of it were ignored: from then on they arrive.
TEST_F(ReassemblerTest, ATypeAddedLaterIsReceivedFromThenOn) {
  TransferReassembler r(table_);
  const CanFrame arming = arming_frame();
  ReceivedTransfer t;
  EXPECT_EQ(r.accept(arming, 0, t), FrameVerdict::kIgnored);
  EXPECT_EQ(r.accept(imu_frames(4, 0, 1.0f)[0], 0, t), FrameVerdict::kInProgress);
  EXPECT_EQ(r.accept(arming, 0, t), FrameVerdict::kIgnored);
  table_.add_message<ArmingStatus>();
  EXPECT_EQ(r.accept(arming, 0, t), FrameVerdict::kTransferComplete);
  EXPECT_EQ(t.type, table_.find(TransferKind::kMessage, ArmingStatus::kType.default_dtid));
}

// Many sources' transfers in flight at once, finishing in another order than they started,
// while single-frame transfers pass between them: each one arrives whole, and every session
// is free again afterwards.
TEST_F(ReassemblerTest, ManyInterleavedTransfersEachArriveWholeAndFreeTheirSessions) {
  ReassemblerConfig config;
  config.max_sessions = 8;
  TransferReassembler r(table_, config);
  std::vector<std::vector<CanFrame>> transfers;
  for (uint8_t node = 1; node <= 8; ++node) transfers.push_back(imu_frames(node, node, node * 1.5f));
  Payload payload;
  std::vector<CanFrame> status;
  ASSERT_TRUE(append_message_frames(NodeStatus{}, message_header<NodeStatus>(20, 0), payload, status).ok());
  std::vector<float> got;
  ReceivedTransfer t;
  const std::size_t frames_each = transfers[0].size();
  for (std::size_t k = 0; k < frames_each; ++k) {
    // Nodes 1-4 in order, 5-8 in reverse: transfers end in another order than they began.
    for (std::size_t n = 0; n < transfers.size(); ++n) {
      const std::size_t node = n < 4 ? n : 11 - n;
      if (r.accept(transfers[node][k], 0, t) == FrameVerdict::kTransferComplete) {
        got.push_back(decode_imu(t).integration_interval);
      }
      ASSERT_EQ(r.accept(status[0], 0, t), FrameVerdict::kTransferComplete);
    }
  }
  EXPECT_EQ(got, (std::vector<float>{1.5f, 3.0f, 4.5f, 6.0f, 12.0f, 10.5f, 9.0f, 7.5f}));
  EXPECT_EQ(r.active_transfers(), 0u);
  EXPECT_EQ(r.stats().rejected_frames(), 0u);
  // All eight sessions are free: eight new transfers fit at once.
  for (uint8_t node = 1; node <= 8; ++node) {
    EXPECT_EQ(r.accept(imu_frames(node, 9, 1.0f)[0], 0, t), FrameVerdict::kInProgress);
  }
}

TEST(CanId, MessageAndServiceIdsRoundTrip) {
  TransferHeader message;
  message.priority = 16;
  message.data_type_id = 1030;
  message.source_node_id = 42;
  EXPECT_EQ(make_can_id(message), 0x1004062Au);  // vectors.json, esc.RawCommand
  EXPECT_EQ(parse_can_id(0x1004062A), message);

  TransferHeader request;
  request.priority = 30;
  request.kind = TransferKind::kRequest;
  request.data_type_id = 200;
  request.source_node_id = 10;
  request.destination_node_id = 99;
  const uint32_t id = make_can_id(request);
  EXPECT_EQ(id, (30u << 24) | (200u << 16) | (1u << 15) | (99u << 8) | 0x80u | 10u);
  EXPECT_EQ(parse_can_id(id), request);
  auto response = request;
  response.kind = TransferKind::kResponse;
  EXPECT_EQ(parse_can_id(make_can_id(response)), response);

  EXPECT_EQ(check_header(request), "");
  request.destination_node_id = 0;
  EXPECT_EQ(check_header(request), "service destination node ID 0 not in 1..127");
  message.priority = 40;
  EXPECT_EQ(check_header(message), "priority 40 > 31");
}

TEST(CanId, ServicesForOtherNodesAreIgnored) {
  DataTypeTable table;
  table.add("test.Service", TransferKind::kRequest, 200, 0x1234, 8);
  ReassemblerConfig config;
  config.local_node_id = 5;
  TransferReassembler r(table, config);
  TransferHeader h;
  h.kind = TransferKind::kRequest;
  h.data_type_id = 200;
  h.source_node_id = 9;
  h.destination_node_id = 6;
  const uint8_t payload[] = {1, 2, 3};
  std::vector<CanFrame> frames;
  append_transfer_frames(h, 0x1234, payload, 3, frames);
  ReceivedTransfer t;
  EXPECT_EQ(r.accept(frames[0], 0, t), FrameVerdict::kIgnored);
  frames.clear();
  h.destination_node_id = 5;
  append_transfer_frames(h, 0x1234, payload, 3, frames);
  EXPECT_EQ(r.accept(frames[0], 0, t), FrameVerdict::kTransferComplete);
  EXPECT_EQ(t.header.kind, TransferKind::kRequest);
  EXPECT_EQ(t.size, 3u);
}

}  // namespace
}  // namespace a3::bridge
