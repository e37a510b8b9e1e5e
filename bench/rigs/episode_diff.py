#!/usr/bin/env python3
"""Compare two trees of episode.json files, ignoring wall-clock fields.

Usage: episode_diff.py BASE_DIR NEW_DIR
Each BASE_DIR/<scenario>/episode.json is compared with NEW_DIR/<scenario>/episode.json
after removing the fields in WALL_CLOCK_FIELDS. Exit 1 on any difference.
"""
import json
import sys
from pathlib import Path

# Fields that record the host's clock, not the episode: (object, field) at the top level.
WALL_CLOCK_FIELDS = [("_meta", "ts"), ("_meta", "ts_iso"), ("_rig", "wall_time_s")]


def strip(episode):
    for section, field in WALL_CLOCK_FIELDS:
        if isinstance(episode.get(section), dict):
            episode[section].pop(field, None)
    return episode


def first_difference(a, b, path="$"):
    if type(a) is not type(b):
        return f"{path}: {a!r} != {b!r}"
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f"{path}.{k}: only in {'new' if k in b else 'base'}"
            d = first_difference(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f"{path}: length {len(a)} != {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_difference(x, y, f"{path}[{i}]")
            if d:
                return d
        return None
    return None if a == b else f"{path}: {a!r} != {b!r}"


def main():
    base, new = Path(sys.argv[1]), Path(sys.argv[2])
    failed = False
    for episode in sorted(base.glob("*/episode.json")):
        other = new / episode.parent.name / "episode.json"
        if not other.exists():
            print(f"{episode.parent.name}: missing in {new}")
            failed = True
            continue
        a = strip(json.loads(episode.read_text()))
        b = strip(json.loads(other.read_text()))
        # Byte-level comparison of the stripped documents, then the first difference if any.
        same = json.dumps(a, sort_keys=False) == json.dumps(b, sort_keys=False)
        print(f"{episode.parent.name}: {'identical' if same else 'DIFFERENT: ' + str(first_difference(a, b))}")
        failed |= not same
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
