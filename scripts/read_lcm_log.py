#!/usr/bin/env python3
"""Reads an a3rig episode's LCM log (episode.lcmlog) with the Python types lcm-gen makes from
lcmtypes/*.lcm, and prints the messages per channel and type, the vehicle state count and the
first and last position.

Usage: read_lcm_log.py RUN_FOLDER_OR_LOG [--types DIR] [--json]
  --types DIR  the folder holding the generated package a3lcm (default: the build tree's
               build/generated/python, or <prefix>/lib/python3/dist-packages when installed)
  --json       one JSON object instead of text

Debian 12 has no Python LCM module, so the log's event framing (lcm-logger's format: sync word,
event number, timestamp, channel length, data length, channel, data; big-endian) is read here
with struct. The generated types decode each message and need nothing but struct.
"""
import argparse
import json
import pathlib
import struct
import sys

SYNC_WORD = 0xEDA1DA01
EVENT_HEADER = struct.Struct(">IqqII")  # sync, event number, timestamp (us), channel len, data len


def default_types_dirs():
    here = pathlib.Path(__file__).resolve().parent
    return [here.parent / "lib" / "python3" / "dist-packages",  # installed: <prefix>/bin
            here.parent / "build" / "generated" / "python"]     # source tree: scripts/


def import_types(types_dir):
    candidates = [pathlib.Path(types_dir)] if types_dir else default_types_dirs()
    for folder in candidates:
        if (folder / "a3lcm" / "__init__.py").is_file():
            sys.path.insert(0, str(folder))
            import a3lcm
            return a3lcm
    sys.exit("read_lcm_log.py: no generated a3lcm package in " +
             ", ".join(str(c) for c in candidates) + " (build the project, or pass --types DIR)")


def types_by_fingerprint(a3lcm):
    types = {}
    for name in dir(a3lcm):
        cls = getattr(a3lcm, name)
        if isinstance(cls, type) and hasattr(cls, "_get_packed_fingerprint"):
            types[cls._get_packed_fingerprint()] = cls
    return types


def read_events(path):
    """Yields (timestamp_us, channel, data) for each event of an LCM log file."""
    with open(path, "rb") as f:
        while header := f.read(EVENT_HEADER.size):
            if len(header) < EVENT_HEADER.size:
                raise ValueError(f"{path}: truncated event header at byte {f.tell() - len(header)}")
            sync, _number, utime_us, channel_len, data_len = EVENT_HEADER.unpack(header)
            if sync != SYNC_WORD:
                raise ValueError(f"{path}: no LCM sync word at byte {f.tell() - len(header)} "
                                 f"(found {sync:#010x}): not an LCM log")
            channel, data = f.read(channel_len), f.read(data_len)
            if len(channel) != channel_len or len(data) != data_len:
                raise ValueError(f"{path}: truncated event at byte {f.tell()}")
            yield utime_us, channel.decode("utf-8"), data


def position(state):
    return {"utime_us": state.utime_us, "p_W_m": list(state.p_W_m)}


def summarize(path, a3lcm):
    types = types_by_fingerprint(a3lcm)
    channels, states, unknown = {}, [], 0
    for _utime_us, channel, data in read_events(path):
        cls = types.get(data[:8])
        if cls is None:
            unknown += 1
            continue
        message = cls.decode(data)
        key = f"{channel} {cls.__name__}"
        channels[key] = channels.get(key, 0) + 1
        if cls is a3lcm.vehicle_state_t:
            states.append(message)
    return {"log": str(path), "channels": channels, "unknown_type_events": unknown,
            "vehicle_states": len(states),
            "first_position": position(states[0]) if states else None,
            "last_position": position(states[-1]) if states else None}


def print_text(summary):
    print(f"log: {summary['log']}")
    for key, count in sorted(summary["channels"].items()):
        print(f"  {key}: {count}")
    print(f"messages of no a3lcm type: {summary['unknown_type_events']}")
    print(f"vehicle states: {summary['vehicle_states']}")
    for which in ("first", "last"):
        p = summary[f"{which}_position"]
        if p:
            x, y, z = p["p_W_m"]
            print(f"{which} position: t={p['utime_us'] / 1e6:.3f} s  "
                  f"p_W_m=({x:.3f}, {y:.3f}, {z:.3f}) m")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("path", help="a run folder (holding episode.lcmlog) or an LCM log file")
    parser.add_argument("--types", help="folder holding the generated package a3lcm")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    path = pathlib.Path(args.path)
    if path.is_dir():
        path = path / "episode.lcmlog"
    if not path.is_file():
        sys.exit(f"read_lcm_log.py: {path}: no such LCM log")
    a3lcm = import_types(args.types)
    try:
        summary = summarize(path, a3lcm)
    except (ValueError, OSError) as e:
        sys.exit(f"read_lcm_log.py: {e}")
    if args.json:
        print(json.dumps(summary))
    else:
        print_text(summary)


if __name__ == "__main__":
    main()
