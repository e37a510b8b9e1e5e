// `a3rig can ...`: look at and talk to a CAN bus. `monitor` prints every DroneCAN transfer
// decoded (and raw frames with --raw), `send` puts a DroneCAN message (fields as JSON) or a
// raw frame on the bus, `types` lists the message types the rig knows. The bus is named as
// for every node: vcan0 (SocketCAN, else the userspace bus of that name), socketcan:NAME,
// userspace:NAME.
#include <CLI/CLI.hpp>

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bridge/can/can_bus_factory.hpp"
#include "bridge/dronecan/message_registry.hpp"
#include "bridge/dronecan/reassembler.hpp"
#include "bridge/dronecan/transfer.hpp"
#include "common/clock.hpp"
#include "common/json_text.hpp"
#include "common/realtime_executor.hpp"
#include "rigs/cli/command_registry.hpp"
#include "rigs/cli/flag_checks.hpp"

namespace a3::rigs {
namespace {

std::atomic<bool> g_interrupted{false};

void on_signal(int) { g_interrupted = true; }

struct MonitorArgs {
  std::string bus;
  uint64_t count = 0;
  double seconds = 0;
  bool raw = false;
  bool quiet_summary = false;
};

std::string kind_text(bridge::TransferKind kind) {
  switch (kind) {
    case bridge::TransferKind::kMessage: return "msg";
    case bridge::TransferKind::kRequest: return "req";
    case bridge::TransferKind::kResponse: return "rsp";
  }
  return "?";
}

int run_monitor(const MonitorArgs& args) {
  auto bus = bridge::open_can_bus(args.bus);
  bridge::DataTypeTable types;
  bridge::add_all_message_types(types);
  bridge::TransferReassembler reassembler(types);
  common::WallClock clock;
  common::RealTimeExecutor executor(clock);
  uint64_t transfers = 0;
  uint64_t decode_failures = 0;
  bus->start(executor, [&](const bridge::CanFrame& frame, int64_t rx_time_us) {
    const double t = rx_time_us * 1e-6;
    if (args.raw) std::printf("%12.6f  frame %s\n", t, bridge::to_cansend_string(frame).c_str());
    bridge::ReceivedTransfer transfer;
    const auto verdict = reassembler.accept(frame, rx_time_us, transfer);
    if (verdict == bridge::FrameVerdict::kRejected) {
      std::printf("%12.6f  rejected %s: %s\n", t, bridge::to_cansend_string(frame).c_str(),
                  std::string(bridge::to_string(reassembler.last_error())).c_str());
    }
    if (verdict != bridge::FrameVerdict::kTransferComplete) return;
    ++transfers;
    std::string body;
    const bridge::MessageTypeEntry* type =
        transfer.header.kind == bridge::TransferKind::kMessage
            ? bridge::find_message_type(transfer.header.data_type_id)
            : nullptr;
    if (type != nullptr) {
      nlohmann::json fields;
      std::string error;
      if (type->decode_to_json(transfer.payload, transfer.size, fields, error)) {
        body = common::dump_json_text(fields);
      } else {
        ++decode_failures;
        body = "undecodable: " + error;
      }
    }
    std::printf("%12.6f  node %3d %s prio %2d tid %2d %s %s\n", t, transfer.header.source_node_id,
                kind_text(transfer.header.kind).c_str(), transfer.header.priority,
                transfer.header.transfer_id,
                type != nullptr ? std::string(type->info.full_name).c_str() : "(anonymous)",
                body.c_str());
    std::fflush(stdout);
    if (args.count > 0 && transfers >= args.count) executor.stop();
  });
  const int64_t end_us = args.seconds > 0 ? clock.now_us() + static_cast<int64_t>(args.seconds * 1e6) : -1;
  executor.schedule_every(100'000, [&] {
    reassembler.expire(clock.now_us());
    if (g_interrupted) executor.stop();
  });
  ::signal(SIGINT, on_signal);
  ::signal(SIGTERM, on_signal);
  std::fprintf(stderr, "a3rig can monitor: listening on %s (Ctrl-C to stop)\n", bus->name().c_str());
  executor.run(end_us);
  bus->stop();
  if (!args.quiet_summary) {
    const auto& s = reassembler.stats();
    std::fprintf(stderr, "a3rig can monitor: %llu frames, %llu transfers, %llu ignored (unknown type), "
                         "%llu rejected, %llu expired, %llu undecodable\n",
                 static_cast<unsigned long long>(s.frames), static_cast<unsigned long long>(transfers),
                 static_cast<unsigned long long>(s.ignored_frames),
                 static_cast<unsigned long long>(s.rejected_frames()),
                 static_cast<unsigned long long>(s.expired_transfers),
                 static_cast<unsigned long long>(decode_failures));
    for (std::size_t i = 0; i < s.rejected.size(); ++i) {
      if (s.rejected[i] == 0) continue;
      std::fprintf(stderr, "  %llu x %s\n", static_cast<unsigned long long>(s.rejected[i]),
                   std::string(bridge::to_string(static_cast<bridge::FrameError>(i))).c_str());
    }
  }
  return 0;
}

struct SendArgs {
  std::string bus;
  std::string type;
  std::string fields = "";
  std::vector<std::string> frames;
  int node_id = 127;
  int priority = bridge::kPriorityMedium;
  int transfer_id = 0;
};

int run_send(const SendArgs& args) {
  std::vector<bridge::CanFrame> frames;
  for (const auto& text : args.frames) {
    std::string error;
    const auto frame = bridge::parse_cansend_string(text, &error);
    if (!frame) throw std::runtime_error("--frame " + error);
    frames.push_back(*frame);
  }
  if (!args.type.empty()) {
    const bridge::MessageTypeEntry* type = bridge::find_message_type(args.type);
    if (type == nullptr) {
      throw std::runtime_error("unknown or ambiguous message type '" + args.type +
                               "' (a3rig can types lists them; use the full name)");
    }
    nlohmann::json fields;
    try {
      fields = common::parse_json_text(args.fields, "--fields");
    } catch (const common::InputError& e) {
      throw std::runtime_error(e.what());
    }
    bridge::Payload payload;
    std::string error;
    if (!type->encode_from_json(fields, payload, error)) throw std::runtime_error(error);
    bridge::TransferHeader header;
    header.priority = static_cast<uint8_t>(args.priority);
    header.data_type_id = type->info.default_dtid;
    header.source_node_id = static_cast<uint8_t>(args.node_id);
    header.transfer_id = static_cast<uint8_t>(args.transfer_id);
    if (const std::string bad = bridge::check_header(header); !bad.empty()) {
      throw std::runtime_error(bad);
    }
    bridge::append_transfer_frames(header, type->info.signature, payload.data(), payload.size, frames);
  }
  if (frames.empty()) throw std::runtime_error("nothing to send: give TYPE FIELDS or --frame");
  auto bus = bridge::open_can_bus(args.bus);
  for (const auto& frame : frames) {
    if (!bus->send(frame)) throw std::runtime_error(bus->name() + " refused a frame");
  }
  // send() only queues: let the transport put everything on the wire.
  for (int i = 0; i < 1000 && bus->tx_pending() > 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::fprintf(stderr, "a3rig can send: %zu frame(s) on %s\n", frames.size(), bus->name().c_str());
  for (const auto& frame : frames) std::printf("%s\n", bridge::to_cansend_string(frame).c_str());
  return bus->tx_pending() == 0 ? 0 : 1;
}

int run_types() {
  std::printf("%-46s %6s %18s %8s\n", "type", "dtid", "signature", "max bits");
  for (const auto& entry : bridge::message_types()) {
    std::printf("%-46s %6u 0x%016llx %8u\n", std::string(entry.info.full_name).c_str(),
                entry.info.default_dtid, static_cast<unsigned long long>(entry.info.signature),
                entry.info.max_bit_length);
  }
  return 0;
}

}  // namespace

A3_REGISTER_COMMAND("60-can", [](CLI::App& app) {
  CLI::App* can = app.add_subcommand(
      "can",
      "Watch and talk to a CAN bus speaking DroneCAN. BUS: vcan0 / can0 (SocketCAN, or the "
      "userspace bus of that name where this kernel has no such interface, with a warning), "
      "socketcan:NAME, userspace:NAME.");
  can->require_subcommand(1);

  auto monitor = std::make_shared<MonitorArgs>();
  CLI::App* mon = can->add_subcommand(
      "monitor", "Print every DroneCAN transfer on the bus, decoded (JSON fields), and rejected frames");
  mon->add_option("bus", monitor->bus, "the CAN bus")->required();
  mon->add_option("-n,--count", monitor->count, "stop after this many transfers");
  mon->add_option("--seconds", monitor->seconds, "stop after this long")->check(a3::rigs::positive());
  mon->add_flag("--raw", monitor->raw, "also print every frame (cansend syntax)");
  mon->add_flag("-q,--quiet", monitor->quiet_summary, "no summary on stderr at the end");
  mon->callback([monitor] { command_exit_status() = run_monitor(*monitor); });

  auto send = std::make_shared<SendArgs>();
  CLI::App* snd = can->add_subcommand(
      "send",
      "Send one DroneCAN message, e.g. a3rig can send vcan0 a3.fc.Command "
      "'{\"seq\":1,\"command\":1,\"target_W_m\":[0,0,0],\"speed_limit_mps\":0,\"yaw_deg\":null}', "
      "or raw frames with --frame 1004062A#0002C5");
  snd->add_option("bus", send->bus, "the CAN bus")->required();
  snd->add_option("type", send->type, "message type (full name, or unique short name)");
  snd->add_option("fields", send->fields, "the message's fields as a JSON object (NaN: null)");
  snd->add_option("--frame", send->frames, "a raw frame, ID#DATA as for cansend (repeatable)");
  snd->add_option("--node-id", send->node_id,
                  "source node ID (default 127). The rig's fc obeys a3.fc.Command only from its command sources "
                  "(by default the bridge, node 20) and refuses, counts and reports the rest")
      ->check(a3::rigs::between(1, 127));
  snd->add_option("--priority", send->priority, "0 (highest) .. 31 (default 16)")->check(a3::rigs::between(0, 31));
  snd->add_option("--transfer-id", send->transfer_id, "0..31 (default 0)")->check(a3::rigs::between(0, 31));
  snd->callback([send] { command_exit_status() = run_send(*send); });

  CLI::App* types = can->add_subcommand("types", "List the DroneCAN message types the rig knows");
  types->callback([] { command_exit_status() = run_types(); });
});

}  // namespace a3::rigs
