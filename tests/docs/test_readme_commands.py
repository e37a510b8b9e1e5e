#!/usr/bin/python3
"""Every command the README and the docs/ pages show runs as written.

Usage: test_readme_commands.py A3RIG SOURCE_DIR WORK_DIR
Exit 0 pass, 1 fail.

Each fenced code block's lines that begin with `build/a3rig` or `scripts/` (continued over
trailing backslashes, comments after `#` dropped) are checked: an a3rig command with
`a3rig --check-args` (its flags, values and the files it needs exist: a renamed flag fails);
`scripts/main.sh ARGS` as the `a3rig run ARGS` it runs; any other script must exist and be
executable. They run in a scratch folder that holds what the pages' commands read as a user's
would (out/run/ from a run, a corpus-like runs/ and a flat/ folder of episodes), with ../shared
beside it; commands that read ../shared (the α³-Bench public episodes) are skipped, with a note,
when it is absent.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def fenced_blocks(text):
    return re.findall(r"^```[^\n]*\n(.*?)^```", text, flags=re.M | re.S)


def commands(block):
    """The block's commands that begin with build/a3rig or scripts/, continuations joined."""
    out, current = [], ""
    for line in block.splitlines():
        current += line.rstrip()
        if current.endswith("\\"):
            current = current[:-1] + " "
            continue
        if current.startswith(("build/a3rig", "scripts/")):
            out.append(current)
        current = ""
    return out


def words_of(command):
    """The command's words up to the first shell operator (&, |, >, ;, &&): what a3rig is given."""
    lexer = shlex.shlex(command, posix=True, punctuation_chars=True)
    lexer.commenters = "#"
    lexer.whitespace_split = True
    words = []
    for word in lexer:
        if word and all(c in "();<>|&" for c in word):
            break
        words.append(word)
    return words


def scratch_folder(work, shared):
    """A user's folder after a first run: out/run/ with its files, runs/ and flat/ with episodes."""
    repo = work / "repo"
    for folder in ("out/run", "runs/me/my-agent/uav", "flat"):
        (repo / folder).mkdir(parents=True, exist_ok=True)
    for name in ("out/run/episode.json", "out/run/episode.lcmlog", "runs/me/my-agent/uav/sc-0001-ep-00.json",
                 "flat/sc-0001-ep-00.json"):
        (repo / name).write_text("{}")
    link = work / "shared"
    if shared.is_dir() and not link.exists():
        link.symlink_to(shared.resolve())
    return repo


def check_a3rig(a3rig, cwd, page, words):
    done = subprocess.run([a3rig, "--check-args", *words], cwd=cwd, capture_output=True, text=True, timeout=60)
    check(done.returncode == 0, f"{page}: a3rig {' '.join(words)}  ({(done.stderr or done.stdout).strip()[:300]})")


def check_command(a3rig, source, cwd, page, command):
    words = words_of(command)
    if any("../shared" in w for w in words) and not (cwd.parent / "shared" / "alphabench").is_dir():
        print(f"note  {page}: skipped (needs ../shared/alphabench, the α³-Bench public episodes): {command}")
        return
    program, args = words[0], words[1:]
    if program == "build/a3rig":
        check_a3rig(a3rig, cwd, page, args)
    elif program == "scripts/main.sh":
        check_a3rig(a3rig, cwd, page, ["run", "--scenario", "survey-field", "--out", "out/run", *args])
    else:
        script = Path(source) / program
        check(script.is_file() and os.access(script, os.X_OK), f"{page}: {program} exists and is executable")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    a3rig, source, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    shared = Path(os.environ.get("A3_SHARED_DIR", source.parent / "shared"))
    shutil.rmtree(work, ignore_errors=True)
    cwd = scratch_folder(work, shared)
    pages = [source / "README.md", *sorted((source / "docs").glob("*.md"))]
    seen = 0
    for page in pages:
        for block in fenced_blocks(page.read_text()):
            for command in commands(block):
                seen += 1
                check_command(a3rig, source, cwd, page.relative_to(source), command)
    check(seen >= 20, f"the README and docs/ show commands ({seen} found)")
    readme = (source / "README.md").read_text()
    check(len(readme.splitlines()) <= 320, f"the README stays about 300 lines ({len(readme.splitlines())})")
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print(f"all {seen} commands check")


if __name__ == "__main__":
    main()
