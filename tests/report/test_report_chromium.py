#!/usr/bin/python3
"""Renders a3rig's episode reports and a sweep index in headless Chromium and checks them.

Usage: test_report_chromium.py A3RIG WORK_DIR
Exit 0 pass, 1 fail, 77 skip (no chromium or python3-pil). The shared corpus is found through
$A3_SHARED_DIR or ../shared beside the source tree; without it that part is skipped with a note.
"""
import html.parser
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def skip(why):
    print("SKIP: " + why)
    sys.exit(77)


class Elements(html.parser.HTMLParser):
    """Counts elements by class and keeps the body's attributes of a dumped DOM."""

    def __init__(self):
        super().__init__()
        self.classes = {}
        self.body = {}
        self.tags = []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        self.tags.append((tag, attrs))
        if tag == "body":
            self.body = attrs
        for c in (attrs.get("class") or "").split():
            self.classes[c] = self.classes.get(c, 0) + 1

    def count(self, cls):
        return self.classes.get(cls, 0)


def chromium(page, *flags):
    cmd = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--enable-logging=stderr",
           "--v=0", "--virtual-time-budget=5000", *flags, page.as_uri()]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    return done.stdout, done.stderr


def render(page, screenshot=None):
    """The page's DOM after its scripts ran, and the screenshot when asked; checks for JS errors."""
    dom, log = chromium(page, "--dump-dom")
    doc = Elements()
    doc.feed(dom)
    check(doc.body.get("data-drawn") == "yes", f"{page.name}: the page's script ran to the end")
    errors = doc.body.get("data-js-errors", "[]")
    console = [line for line in log.splitlines() if "CONSOLE" in line and ("Uncaught" in line or "rror" in line)]
    check(errors in ("[]", None) and not console, f"{page.name}: no JavaScript errors ({errors}; {console[:3]})")
    if screenshot:
        chromium(page, f"--screenshot={screenshot}", "--window-size=1400,1400")
    return doc


def inked(png, box):
    """Share of non-background pixels and distinct colours inside box (x, y, w, h)."""
    from PIL import Image
    x, y, w, h = box
    region = Image.open(png).convert("RGB").crop((x, y, x + w, y + h))
    pixels = list(region.getdata())
    ink = sum(1 for p in pixels if p != (255, 255, 255))
    return ink / max(1, len(pixels)), len(set(pixels))


def box_of(doc, name):
    return [int(v) for v in doc.body[name].split(",")]


def run_episode(a3rig, work, scenario, *flags):
    out = work / scenario
    subprocess.run([a3rig, "run", "--runtime", "virtual", "--scenario", scenario, "--out", str(out), "--no-lcm-log",
                    "--no-plot", "--quiet", *flags], check=False, timeout=300)
    return out


def check_run_report(a3rig, work, scenario, flags, expect):
    out = run_episode(a3rig, work, scenario, *flags)
    page = out / "report.html"
    check(page.is_file(), f"{scenario}: a3rig run wrote report.html beside episode.json")
    if not page.is_file():
        return
    episode = json.loads((out / "episode.json").read_text())
    png = work / f"{scenario}.png"
    doc = render(page, png)
    agent_turns = sum(1 for t in episode["dialogue"] if t["speaker"] == "agent")
    events = episode["_rig"]["safety_events"]
    check(doc.count("track-seg") == agent_turns > 0, f"{scenario}: one track segment per agent turn ({doc.count('track-seg')} / {agent_turns})")
    check(doc.count("event-marker") == len(events), f"{scenario}: one marker per safety event ({doc.count('event-marker')} / {len(events)})")
    check(doc.count("turn-row") == len(episode["dialogue"]), f"{scenario}: one dialogue row per turn")
    for cls, least in expect.items():
        check(doc.count(cls) >= least, f"{scenario}: at least {least} '{cls}' drawn ({doc.count(cls)})")
    if png.is_file():
        for name in ("data-map-box", "data-timelines-box"):
            share, colours = inked(png, box_of(doc, name))
            check(share > 0.01 and colours > 8, f"{scenario}: {name[5:]} has drawn pixels ({share:.1%}, {colours} colours)")
    return png


def check_corpus_report(a3rig, work):
    shared = Path(os.environ.get("A3_SHARED_DIR", SOURCE.parent / "shared"))
    runs = sorted((shared / "alphabench" / "eval_runs").glob("*/*/uav/sc-0001-ep-00.json"))
    if not runs:
        print(f"note: no public corpus under {shared}/alphabench (get it from the α³-Bench public release, or set A3_SHARED_DIR): corpus report not checked")
        return
    page = work / "corpus.html"
    subprocess.run([a3rig, "report", str(runs[0]), "-o", str(page)], check=True, timeout=120)
    episode = json.loads(runs[0].read_text())
    doc = render(page)
    check(doc.count("turn-row") == len(episode["dialogue"]), "corpus episode: one dialogue row per turn")
    nets = sum(1 for tag, attrs in doc.tags if tag == "svg" and (attrs.get("data-name") or "").startswith("net-"))
    check(nets >= 1 and doc.count("turn-bar") == len(episode["dialogue"]), f"corpus episode: net timelines ({nets}) and turn bars drawn")


def check_sweep_index(a3rig, work):
    out = work / "sweep"
    subprocess.run([a3rig, "sweep", "--scenarios", "traffic-conflict", "--think-times", "0,90", "--slices", "URLLC",
                    "--seeds", "1", "--jobs", "2", "--out", str(out)], check=True, timeout=600, stdout=subprocess.DEVNULL)
    page = out / "index.html"
    check(page.is_file(), "sweep: index.html written")
    if not page.is_file():
        return
    doc = render(page)
    check(doc.count("cell") == 2, f"sweep index: a row per cell ({doc.count('cell')})")
    check(int(doc.body.get("data-plots-loaded", "0")) >= 1, "sweep index: the aggregate plot loads")
    links = [attrs["href"] for tag, attrs in doc.tags if tag == "a"]
    check(len(links) == 2 and all(l.endswith("report.html") and (out / l).is_file() for l in links),
          f"sweep index: every cell links to its report ({links})")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    if not CHROMIUM:
        skip("no chromium (Debian: apt-get install chromium)")
    try:
        import PIL  # noqa: F401
    except ImportError:
        skip("no PIL for /usr/bin/python3 (Debian: apt-get install python3-pil)")
    a3rig, work = sys.argv[1], Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    png = check_run_report(a3rig, work, "traffic-conflict", ["--think-time", "90"],
                           {"peer-plan": 1, "geofence": 1, "objective-point": 1, "home": 1, "event-marker": 1})
    check_run_report(a3rig, work, "nfz-detour", [], {"zone": 1, "zone-label": 1})
    check_corpus_report(a3rig, work)
    check_sweep_index(a3rig, work)
    if png and os.environ.get("A3_REPORT_PNG"):
        shutil.copyfile(png, os.environ["A3_REPORT_PNG"])
        print("screenshot: " + os.environ["A3_REPORT_PNG"])
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)


if __name__ == "__main__":
    main()
