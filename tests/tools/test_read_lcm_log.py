#!/usr/bin/env python3
"""scripts/read_lcm_log.py on a run's episode.lcmlog: every message decodes with the generated
Python types, and the vehicle track it reads starts at the episode's initial pose and ends at its
final pose (episode.json, written by the rig's C++ recorder from the bus, not from the log).
Usage: test_read_lcm_log.py READ_LCM_LOG_PY TYPES_DIR RUN_DIR
"""
import json
import math
import pathlib
import subprocess
import sys

TOLERANCE_M = 0.05  # the recorder's last state and the log's may be one 4 ms step apart in flight


def pose_of(state):
    pose = state["uav"]["pose"]
    return [pose["x"], pose["y"], pose["z"]]


def check(condition, message):
    if not condition:
        sys.exit(f"FAIL: {message}")
    print(f"ok: {message}")


def main():
    script, types_dir, run_dir = sys.argv[1:4]
    out = subprocess.run([sys.executable, script, run_dir, "--types", types_dir, "--json"],
                         capture_output=True, text=True, check=False)
    if out.returncode != 0:
        sys.exit(f"FAIL: read_lcm_log.py exited {out.returncode}: {out.stderr}")
    summary = json.loads(out.stdout)
    episode = json.loads((pathlib.Path(run_dir) / "episode.json").read_text())
    states_on_channel = sum(n for key, n in summary["channels"].items() if key.endswith(" vehicle_state_t"))
    check(summary["unknown_type_events"] == 0, "every message of the log has an a3lcm type")
    check(summary["vehicle_states"] > 100, f"{summary['vehicle_states']} vehicle states read")
    check(states_on_channel == summary["vehicle_states"], "the per-channel counts add up to the vehicle states")
    check(len(summary["channels"]) >= 5, f"{len(summary['channels'])} channel/type pairs read")
    first, last = summary["first_position"]["p_W_m"], summary["last_position"]["p_W_m"]
    initial, final = pose_of(episode["initial_state"]), pose_of(episode["final_state"])
    check(math.dist(first, initial) < TOLERANCE_M, f"first position {first} is the initial pose {initial}")
    check(math.dist(last, final) < TOLERANCE_M, f"last position {last} is the final pose {final}")


if __name__ == "__main__":
    main()
