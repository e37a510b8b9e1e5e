#!/usr/bin/env python3
"""How real is real time? Flies missions with `a3rig run` in real time for each requested
real-time factor and number of busy-loop processes (each burns a core), and prints per cell:
the achieved real-time factor over the flight, the worst 1 s window, the vehicle nodes' step
lateness p99 (the worst of dynamics, bridge and fc), the lockstep waits (count and wall time),
the stale dynamics steps, the status, and whether the outcome (status, success, safety flags,
turns, SP) matched the virtual-time run of the same mission and seed.

  python3 bench/rigs/realtime_matrix.py                       # the README's table (~50 min)
  python3 bench/rigs/realtime_matrix.py --rtf 4,8 --busy 2 --scenarios traffic-conflict
  python3 bench/rigs/realtime_matrix.py --sync free           # the free-running mode

Needs a built a3rig (build/a3rig) and LCM multicast on loopback (scripts/lcm-loopback.sh)."""
import argparse
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(a3rig, scenario, out, extra):
    cmd = [a3rig, "run", "--scenario", scenario, "--out", out, "--no-plot", "--no-lcm-log", "-q"] + extra
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    with open(os.path.join(out, "episode.json")) as f:
        return json.load(f)


def outcome(e):
    flags = sorted(k for k, v in e["final_state"]["safety_flags"].items() if v is True)
    turns = [t.get("speaker", "") + " " + t.get("intent", "") for t in e["dialogue"]]
    status = e["_rig"]["status"].split(":")[0]
    return (status, e["success"], flags, turns)


def busy_loops(n):
    procs = []
    for _ in range(n):
        procs.append(subprocess.Popen([sys.executable, "-c", "while True: pass"]))
    return procs


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--a3rig", default=os.path.join(REPO, "build", "a3rig"))
    p.add_argument("--scenarios", default="survey-field,traffic-conflict")
    p.add_argument("--rtf", default="1,2,4,8")
    p.add_argument("--busy", default="0,1,2")
    p.add_argument("--sync", default="lockstep", choices=["lockstep", "free"])
    p.add_argument("--processes", action="store_true", help="the vehicle's nodes as processes of their own")
    p.add_argument("--seed", default="42")
    a = p.parse_args()
    tmp = tempfile.mkdtemp(prefix="a3-rt-matrix-")
    print(f"real-time matrix: sync {a.sync}{' (processes)' if a.processes else ''}, seed {a.seed}, "
          f"{os.cpu_count()} cores; load average {os.getloadavg()[0]:.2f}")
    print(f"{'scenario':18} {'rtf':>4} {'busy':>4} {'achieved':>9} {'worst 1s':>9} {'p99 us':>8} "
          f"{'waits':>8} {'wait s':>7} {'stale':>6} {'wall s':>7}  status / matches virtual")
    for scenario in a.scenarios.split(","):
        virtual = run(a.a3rig, scenario, os.path.join(tmp, f"{scenario}-virtual"),
                      ["--runtime", "virtual", "--seed", a.seed])
        for rtf in a.rtf.split(","):
            for busy in [int(b) for b in a.busy.split(",")]:
                out = os.path.join(tmp, f"{scenario}-{rtf}-{busy}")
                load = busy_loops(busy)
                t0 = time.monotonic()
                try:
                    extra = ["--rtf", rtf, "--sync", a.sync, "--seed", a.seed] + (["--processes"] if a.processes else [])
                    e = run(a.a3rig, scenario, out, extra)
                finally:
                    for proc in load:
                        proc.send_signal(signal.SIGKILL)
                        proc.wait()
                wall = time.monotonic() - t0
                rt = e["_rig"].get("realtime", {})
                nodes = rt.get("nodes", {})
                p99 = max((nodes.get(n, {}).get("lateness_p99_us", 0.0) for n in ("dynamics", "bridge", "fc")),
                          default=0.0)
                lock = rt.get("lockstep") or {}
                same = outcome(e) == outcome(virtual)
                print(f"{scenario:18} {rtf:>4} {busy:>4} {rt['rtf']['achieved']:9.4f} {rt['rtf']['worst_window']:9.3f} "
                      f"{p99:8.0f} {lock.get('waits', 0):8.0f} {lock.get('wait_total_s', 0):7.2f} "
                      f"{rt.get('stale_steps', 0):6d} {wall:7.1f}  {e['_rig']['status'][:40]} / "
                      f"{'yes' if same else 'NO'}", flush=True)


if __name__ == "__main__":
    main()
