#!/usr/bin/env python3
"""Whole-episode speed in virtual time: simulated seconds per wall second and per CPU second.

Runs `a3rig run --runtime virtual` (no LCM log, plot or report: the flight and the episode only)
on each scenario --repeat times and prints the best run, then, when `perf` works, the top
symbols of one recorded run.

With --sweep it then runs the README's latency-sensitivity sweep (every built-in scenario,
7 think times x 3 slices x --sweep-seeds, `a3rig sweep --jobs 2`, into a temporary folder) and
prints its wall time and episodes per second: about 5 minutes for the 630 episodes.

usage: bench/rigs/episode_speed.py [--a3rig build/a3rig] [--scenarios survey-field,traffic-conflict]
                                   [--repeat 5] [--top 5] [--no-perf] [--sweep [--sweep-seeds 1-5]]
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import tempfile
import time


def run_once(a3rig, scenario, out):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run([a3rig, "run", "--runtime", "virtual", "--scenario", scenario, "--out", out, "--quiet",
                    "--no-lcm-log", "--no-plot", "--no-report"], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    wall_s = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu_s = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(os.path.join(out, "episode.json")) as f:
        mission_s = json.load(f)["_rig"]["mission_time_s"]
    return mission_s, wall_s, cpu_s


def top_symbols(a3rig, scenario, out, top):
    os.makedirs(out, exist_ok=True)
    data = os.path.join(out, "perf.data")
    record = subprocess.run(["perf", "record", "-q", "-o", data, "--", a3rig, "run", "--runtime", "virtual",
                             "--scenario", scenario, "--out", out, "--quiet", "--no-lcm-log", "--no-plot",
                             "--no-report"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    if record.returncode != 0:
        return [f"(perf record failed with exit status {record.returncode}: perf_event_paranoid?)"]
    report = subprocess.run(["perf", "report", "-q", "-i", data, "--stdio", "--sort", "symbol", "--percent-limit", "0.5"],
                            capture_output=True, text=True)
    lines = []
    for line in report.stdout.splitlines():
        words = line.split()
        if len(words) >= 3 and words[0].endswith("%") and words[1] == "[.]":
            lines.append(f"{words[0]:>7}  {' '.join(w for w in words[2:] if w != '-')}")
    return lines[:top]


def sweep_wall_time(a3rig, seeds, out):
    """Runs the default sweep grid with `seeds`; returns (episodes, wall s)."""
    start = time.monotonic()
    done = subprocess.run([a3rig, "sweep", "--jobs", "2", "--seeds", seeds, "--out", out],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall_s = time.monotonic() - start
    if done.returncode != 0:
        raise SystemExit(f"a3rig sweep exited with status {done.returncode}:\n{done.stdout[-2000:]}")
    with open(os.path.join(out, "results.csv")) as f:
        episodes = sum(1 for _ in f) - 1
    return episodes, wall_s


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--a3rig", default="build/a3rig")
    parser.add_argument("--scenarios", default="survey-field,traffic-conflict")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--top", type=int, default=5)
    parser.add_argument("--no-perf", action="store_true")
    parser.add_argument("--sweep", action="store_true", help="also time the README's sweep (minutes)")
    parser.add_argument("--sweep-seeds", default="1-5")
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="a3-episode-speed-")
    try:
        print(f"{'scenario':<18} {'mission s':>9} {'wall s':>7} {'CPU s':>6} {'sim s / wall s':>15} {'sim s / CPU s':>14}")
        for scenario in args.scenarios.split(","):
            runs = [run_once(args.a3rig, scenario, os.path.join(work, f"{scenario}-{i}")) for i in range(args.repeat)]
            mission_s, wall_s, cpu_s = min(runs, key=lambda r: r[1])
            print(f"{scenario:<18} {mission_s:9.1f} {wall_s:7.2f} {cpu_s:6.2f} {mission_s / wall_s:15.0f} {mission_s / cpu_s:14.0f}")
            if not args.no_perf and shutil.which("perf"):
                for line in top_symbols(args.a3rig, scenario, os.path.join(work, f"{scenario}-perf"), args.top):
                    print(f"    {line}")
        if args.sweep:
            episodes, wall_s = sweep_wall_time(args.a3rig, args.sweep_seeds, os.path.join(work, "sweep"))
            print(f"sweep, every built-in scenario, seeds {args.sweep_seeds}, --jobs 2: {episodes} episodes "
                  f"in {wall_s:.0f} s wall ({episodes / wall_s:.2f} episodes/s)")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
