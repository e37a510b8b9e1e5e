#!/usr/bin/python3
"""Text from outside never runs as code in what a3rig writes: reports, the sweep index, its plots.

Usage: test_report_untrusted.py A3RIG WORK_DIR
Exit 0 pass, 1 fail, 77 skip (no chromium).

1. A real episode (traffic-conflict, slow agent: safety events) has every string value, and the
   keys of its tool arguments and observations, replaced by classic payloads (event-handler
   attributes, </script>, javascript: URLs, SVG with script, CSS expressions, iframes); its file
   name carries one too. `a3rig report` draws it; headless Chromium must run the page's own script
   to the end, run none of the payloads (no data-pwned, no CSP violation: nothing
   even tried), create none of the planted elements, and show the payloads as text.
2. The same page with markup slipped in by hand (an inline handler and an inline script): the
   page's Content-Security-Policy blocks both, and the page still draws.
3. A sweep folder whose results.csv has payloads for scenario names, agents, think times, slices,
   statuses and episode paths (and formula leads for spreadsheets), in a folder whose name holds
   shell and gnuplot syntax: `a3rig sweep --plot-only` writes an index that runs none of them and
   links only below itself, plots whose scripts ran no command, and CSV cells kept as text.
"""
import html.parser
import json
import shutil
import subprocess
import sys
from pathlib import Path

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
failures = []

PWN = "document.body.setAttribute('data-pwned','{0}')"
PAYLOADS = [
    '<img src=x onerror="' + PWN.format("img") + '" data-planted="img">',
    "</script><script data-planted=\"script\">" + PWN.format("script") + "</script>",
    '<a data-planted="a" href="javascript:' + PWN.format("href") + '">click</a>',
    '<svg data-planted="svg" onload="' + PWN.format("svg") + '"><script>' + PWN.format("svgscript") + "</script></svg>",
    '<div data-planted="css" style="background:url(javascript:' + PWN.format("css") + ');width:expression(alert(1))">x</div>',
    "<iframe data-planted=\"iframe\" src=\"javascript:" + PWN.format("iframe") + "\"></iframe>",
    "\"><body onload=\"" + PWN.format("attr") + "\" data-planted=\"attr\">",
    "'-alert(1)-'\u2028<style data-planted=\"style\">body{display:none}</style>",
    "javascript:" + PWN.format("bare") + "//",
    "<math><mtext><table><mglyph><style><img src=x onerror=\"" + PWN.format("mxss") + "\" data-planted=\"mxss\">",
]
FILE_PAYLOAD = '"><svg onload=' + PWN.format("file").replace("/", "") + " data-planted=file>"


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


class Dom(html.parser.HTMLParser):
    """Elements and text of a dumped DOM."""

    def __init__(self):
        super().__init__()
        self.tags = []
        self.text = []

    def handle_starttag(self, tag, attrs):
        self.tags.append((tag, dict(attrs)))

    def handle_data(self, data):
        self.text.append(data)

    def attrs_named(self, name):
        return [(tag, attrs) for tag, attrs in self.tags if name in attrs]

    def body(self):
        return next((attrs for tag, attrs in self.tags if tag == "body"), {})


def render(page):
    cmd = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--enable-logging=stderr", "--v=0",
           "--virtual-time-budget=5000", "--dump-dom", page.as_uri()]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    dom = Dom()
    dom.feed(done.stdout)
    return dom, done.stderr


def csp_violations(log):
    return [line for line in log.splitlines() if "Content Security Policy" in line or "Content-Security-Policy" in line]


def check_nothing_ran(dom, log, what, expect_violations=False):
    body = dom.body()
    check(body.get("data-drawn") == "yes", f"{what}: the page's own script ran to the end")
    pwned = [attrs.get("data-pwned") for tag, attrs in dom.attrs_named("data-pwned")]
    check(not pwned, f"{what}: no payload ran ({pwned})")
    violations = csp_violations(log)
    if expect_violations:
        check(len(violations) > 0, f"{what}: the browser reports the Content-Security-Policy blocking the slipped markup")
    else:
        check(not violations, f"{what}: nothing even tried to run ({violations[:2]})")


def poisoned(value, counter):
    """Every string replaced by the next payload; the keys of args and obs objects too."""
    if isinstance(value, str):
        counter[0] += 1
        return PAYLOADS[counter[0] % len(PAYLOADS)]
    if isinstance(value, list):
        return [poisoned(v, counter) for v in value]
    if isinstance(value, dict):
        out = {k: poisoned(v, counter) for k, v in value.items()}
        for key in ("args", "obs"):
            if isinstance(out.get(key), dict):
                out[key][PAYLOADS[counter[0] % len(PAYLOADS)]] = PAYLOADS[(counter[0] + 3) % len(PAYLOADS)]
        return out
    return value


def check_report(a3rig, work):
    base = work / "base"
    subprocess.run([a3rig, "run", "--runtime", "virtual", "--scenario", "traffic-conflict", "--think-time", "90",
                    "--out", str(base), "--no-lcm-log", "--no-plot", "--quiet"], check=False, timeout=300)
    episode = json.loads((base / "episode.json").read_text())
    check(len(episode["_rig"]["safety_events"]) > 0, "the base episode has safety events (their kinds go in the legend)")
    hostile = poisoned(episode, [0])
    source = work / (FILE_PAYLOAD + ".json")
    source.write_text(json.dumps(hostile))
    page = work / "hostile.html"
    done = subprocess.run([a3rig, "report", str(source), "-o", str(page)], capture_output=True, text=True, timeout=120)
    check(done.returncode == 0 and page.is_file(), f"a3rig report draws the hostile episode ({done.stderr.strip()[-300:]})")
    if not page.is_file():
        return None
    written = Dom()
    written.feed(page.read_text())
    policies = [attrs.get("content", "") for tag, attrs in written.tags
                if tag == "meta" and attrs.get("http-equiv") == "Content-Security-Policy"]
    check(len(policies) == 1 and "script-src 'sha256-" in policies[0] and "default-src 'none'" in policies[0],
          f"the report carries a Content-Security-Policy with hashed scripts ({policies})")
    dom, log = render(page)
    check_nothing_ran(dom, log, "hostile report")
    planted = [attrs.get("data-planted") for tag, attrs in dom.attrs_named("data-planted")]
    check(not planted, f"hostile report: no planted element exists ({planted})")
    shown = "".join(dom.text)
    check(sum(1 for p in PAYLOADS if p in shown) >= 5, "hostile report: the payloads are shown as text")
    check(len([1 for tag, attrs in dom.tags if attrs.get("class") == "turn-row"]) == len(episode["dialogue"]),
          "hostile report: one dialogue row per turn still")
    return page


def check_slip_blocked(page, work):
    slipped = work / "slipped.html"
    slip = ('<img src=x onerror="' + PWN.format("slip-handler") + '">'
            '<script>' + PWN.format("slip-inline") + "</script>"
            '<iframe src="javascript:parent.' + PWN.format("slip-iframe") + '"></iframe>')
    slipped.write_text(page.read_text().replace("<body>", "<body>" + slip, 1))
    dom, log = render(slipped)
    check_nothing_ran(dom, log, "report with slipped markup", expect_violations=True)


RESULTS_HEADER = ("scenario,agent,think_time,think_time_mean_s,slice,seed,status,success,valid,alpha3,TO,SP,TC,IQ,NR,"
                  "CC,mission_time_s,wall_time_s,episode")
GNUPLOT_PAYLOADS = ['x"; system("touch PWNED-gnuplot-dq"); print "', "x'; system('touch PWNED-gnuplot-sq'); print '",
                    "x\nsystem('touch PWNED-gnuplot-nl')", "`touch PWNED-gnuplot-bq`"]
SHEET_PAYLOAD = '=HYPERLINK("http://attacker.example","x")'


def csv_cell(text):
    return '"' + text.replace('"', '""') + '"'


def results_csv():
    rows = [RESULTS_HEADER]
    names = PAYLOADS + GNUPLOT_PAYLOADS + [SHEET_PAYLOAD]
    episodes = ["javascript:" + PWN.format("link"), "../../../etc/passwd", "/etc/passwd",
                "cells/<svg onload=" + PWN.format("path").replace("/", "") + ">/episode.json"]
    for i, name in enumerate(names):
        think = PAYLOADS[(i + 1) % len(PAYLOADS)].replace("\n", " ")
        fields = [name.replace("\n", " "), PAYLOADS[(i + 2) % len(PAYLOADS)], think, str(i), "eMBB" if i % 2 else PAYLOADS[i % len(PAYLOADS)],
                  "1", PAYLOADS[(i + 4) % len(PAYLOADS)], "1", "1", "0.5", "1", "1", "1", "1", "1", "1", "10", "1",
                  episodes[i % len(episodes)]]
        rows.append(",".join(csv_cell(f) for f in fields))
    return "\n".join(rows) + "\n"


def check_sweep(a3rig, work):
    folder = work / "sweep $(touch PWNED-shell) 'x'; touch PWNED-shell2 #"
    folder.mkdir()
    (folder / "results.csv").write_text(results_csv())
    done = subprocess.run([a3rig, "sweep", "--plot-only", str(folder)], capture_output=True, text=True, timeout=300, cwd=work)
    check(done.returncode in (0, 1) and (folder / "index.html").is_file(),
          f"a3rig sweep --plot-only writes the index (exit {done.returncode}; {done.stderr.strip()[-300:]})")
    created = sorted(p.name for p in list(work.rglob("PWNED*")) + list(Path("/tmp").glob("PWNED*")))
    check(not created, f"no shell or gnuplot command ran from names and paths ({created})")
    if not (folder / "index.html").is_file():
        return
    dom, log = render(folder / "index.html")
    check_nothing_ran(dom, log, "hostile sweep index")
    planted = [attrs.get("data-planted") for tag, attrs in dom.attrs_named("data-planted")]
    check(not planted, f"hostile sweep index: no planted element exists ({planted})")
    hrefs = [attrs.get("href", "") for tag, attrs in dom.tags if tag == "a"]
    check(hrefs and all(h.startswith("./") and ":" not in h for h in hrefs),
          f"hostile sweep index: links are relative paths below the sweep ({hrefs})")
    aggregate = (folder / "aggregate.csv").read_text()
    check(csv_cell("'" + SHEET_PAYLOAD) in aggregate, "aggregate.csv: a formula-looking scenario name is kept as text")
    results = (folder / "results.csv").read_text()
    check(csv_cell("'" + SHEET_PAYLOAD) in results, "results.csv: a formula-looking scenario name is kept as text")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    if not CHROMIUM:
        print("SKIP: no chromium (Debian: apt-get install chromium)")
        sys.exit(77)
    a3rig, work = str(Path(sys.argv[1]).resolve()), Path(sys.argv[2]).resolve()
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    page = check_report(a3rig, work)
    if page:
        check_slip_blocked(page, work)
    check_sweep(a3rig, work)
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
