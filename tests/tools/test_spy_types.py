#!/usr/bin/env python3
"""The Java types jar through lcm-spy's own class loading (SpyTypeCheck: lcm.spy.LCMTypeDatabase
over the class path): it finds every a3lcm type, decodes every message of a run's episode.lcmlog,
and reads the same channels, counts and first/last positions as scripts/read_lcm_log.py with the
Python types. Exit 77 (skipped) when java or the jars are absent.
Usage: test_spy_types.py JAVA CLASS_PATH N_TYPES READ_LCM_LOG_PY TYPES_DIR RUN_DIR
  CLASS_PATH  lcm.jar:a3lcm-types.jar:spy-type-check.jar[:jchart2d.jar]
"""
import json
import math
import os
import pathlib
import re
import subprocess
import sys

SKIP = 77


def check(condition, message):
    if not condition:
        sys.exit(f"FAIL: {message}")
    print(f"ok: {message}")


def parse_java(text):
    """SpyTypeCheck's text: '  <channel> <type>: <n>' lines and '<which> position: ... p_W_m=(x, y, z) m'."""
    channels = dict(re.findall(r"^  (\S+ \S+): (\d+)$", text, re.M))
    positions = {w: [float(v) for v in xyz] for w, *xyz in
                 re.findall(r"^(first|last) position: .*p_W_m=\(([-\d.]+), ([-\d.]+), ([-\d.]+)\) m$", text, re.M)}
    found = re.search(r"^Found (\d+) LCM types$", text, re.M)
    return {k: int(v) for k, v in channels.items()}, positions, int(found.group(1)) if found else None


def main():
    java, class_path, n_types, script, types_dir, run_dir = sys.argv[1:7]
    missing = [p for p in [java] + class_path.split(":") if not p or not os.path.exists(p)]
    if missing:
        print(f"skipped: not found: {', '.join(missing) or 'java'} "
              "(Debian: default-jdk-headless, liblcm-java; the build makes the jars when both are there)")
        sys.exit(SKIP)
    log = str(pathlib.Path(run_dir) / "episode.lcmlog")
    spy = subprocess.run([java, "-cp", class_path, "SpyTypeCheck", log], capture_output=True, text=True)
    print(spy.stdout + spy.stderr)
    check(spy.returncode == 0, f"SpyTypeCheck decoded every message (exit {spy.returncode})")
    py = subprocess.run([sys.executable, script, run_dir, "--types", types_dir, "--json"],
                        capture_output=True, text=True, check=True)
    summary = json.loads(py.stdout)
    channels, positions, found = parse_java(spy.stdout + spy.stderr)
    check(found == int(n_types), f"lcm-spy's type database found {found} LCM types, the {n_types} of lcmtypes/")
    check(channels == summary["channels"], f"Java and Python read the same {len(channels)} channel/type counts")
    for which in ("first", "last"):
        java_p, python_p = positions[which], summary[f"{which}_position"]["p_W_m"]
        check(math.dist(java_p, python_p) < 0.002, f"{which} position: Java {java_p}, Python {python_p}")


if __name__ == "__main__":
    main()
