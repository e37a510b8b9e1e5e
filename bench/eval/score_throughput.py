#!/usr/bin/python3
"""Scoring throughput and memory of `a3rig score`, against a plain Python scorer.

Replicates the public α³-Bench episodes (../shared/alphabench) into a corpus of N files
(default 10,000; the same <provider>/<model>/<domain>/sc-XXXX-ep-YY.json layout, each public
file copied under new episode numbers), then times:
  - `a3rig score` (schema validation included) with 1 and 2 threads, best of --repeat runs;
  - the Python reference scorer bench/eval/py_score.py without validation, and with
    jsonschema.Draft202012Validator validation;
and reports episodes/s, MB/s, the ratio, and peak resident memory for two corpus sizes
(N and 4N: memory must not grow with the number of episodes).

usage: bench/eval/score_throughput.py [--build DIR] [--files N] [--repeat K] [--work DIR]
                                      [--python-files N]
"""
import argparse, glob, os, resource, shutil, subprocess, sys, tempfile, time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))


def shared_corpus():
    root = os.environ.get("A3_SHARED_DIR", os.path.join(REPO, "..", "shared"))
    path = os.path.join(root, "alphabench", "eval_runs")
    if not os.path.isdir(path):
        sys.exit("needs the α³-Bench public episodes in %s (put ../shared beside the repository "
                 "or set A3_SHARED_DIR)" % path)
    return path


def replicate(dst, n_files):
    """Copies the public files under new episode numbers until there are n_files."""
    src = shared_corpus()
    files = sorted(glob.glob(os.path.join(src, "*", "*", "*", "sc-*-ep-*.json")))
    copies = -(-n_files // len(files))
    made = 0
    for ep in range(copies):
        for f in files:
            if made >= n_files:
                return made
            rel = os.path.relpath(os.path.dirname(f), src)
            sc = os.path.basename(f).split("-")[1]
            d = os.path.join(dst, rel)
            os.makedirs(d, exist_ok=True)
            dst_file = os.path.join(d, "sc-%s-ep-%04d.json" % (sc, ep))
            try:
                os.link(f, dst_file)  # hard links: a 40k-file corpus costs no disk
            except OSError:
                shutil.copyfile(f, dst_file)
            made += 1
    return made


def corpus_bytes(root):
    return sum(os.path.getsize(os.path.join(dp, f)) for dp, _, fs in os.walk(root) for f in fs)


def timed(cmd):
    """Runs cmd; returns its wall time in seconds."""
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        sys.exit("failed: %s\n%s" % (" ".join(cmd), proc.stderr))
    return wall


def peak_rss_mib(cmd):
    """Peak RSS of cmd, measured in a separate Python process so earlier children don't count."""
    probe = ("import resource,subprocess,sys;"
             "subprocess.run(sys.argv[1:],stdout=subprocess.DEVNULL,stderr=subprocess.DEVNULL);"
             "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)")
    out = subprocess.run([sys.executable, "-c", probe] + cmd, capture_output=True, text=True)
    return int(out.stdout.strip()) / 1024.0


def best_of(cmd, repeat):
    return min(timed(cmd) for _ in range(repeat))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(REPO, "build"))
    ap.add_argument("--files", type=int, default=10000)
    ap.add_argument("--python-files", type=int, default=2000,
                    help="files for the (slow) validating Python run (default 2000)")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--work", help="where to build the corpora (default: a temp folder)")
    args = ap.parse_args()
    a3rig = os.path.join(args.build, "a3rig")
    if not os.access(a3rig, os.X_OK):
        sys.exit("build a3rig first (scripts/setup.sh): %s" % a3rig)
    work = args.work or tempfile.mkdtemp(prefix="a3rig-bench-")
    big, huge, pyc = (os.path.join(work, d) for d in ("big", "huge", "python"))
    for d, n in ((big, args.files), (huge, 4 * args.files), (pyc, args.python_files)):
        if not os.path.isdir(d):
            replicate(d, n)
    n_big = sum(1 for _ in glob.iglob(os.path.join(big, "*", "*", "*", "*.json")))
    mb_big = corpus_bytes(big) / 1e6
    print("corpus: %d files, %.1f MB (%s)" % (n_big, mb_big, big))
    print("machine: %d CPUs" % os.cpu_count())

    # Warm the page cache: we measure scoring, not the disk.
    subprocess.run([a3rig, "score", "-q", "--format", "csv", big], stdout=subprocess.DEVNULL)
    results = {}
    for threads in (1, 2):
        wall = best_of([a3rig, "score", "-q", "--format", "csv", "--threads", str(threads), big], args.repeat)
        results[threads] = n_big / wall
        print("a3rig score, %d thread%s, validation included: %8.0f episodes/s  %6.1f MB/s  (best of %d: %.3f s)"
              % (threads, "" if threads == 1 else "s", n_big / wall, mb_big / wall, args.repeat, wall))
    per_113k = 113000 / results[2]
    print("  -> the paper's 113k-episode corpus at this rate: %.1f s" % per_113k)

    py = ["/usr/bin/python3", os.path.join(HERE, "py_score.py")]
    wall = best_of(py + ["--no-validate", big], 1)
    py_plain = n_big / wall
    print("python scorer, no validation:            %8.0f episodes/s" % py_plain)
    n_py = sum(1 for _ in glob.iglob(os.path.join(pyc, "*", "*", "*", "*.json")))
    wall = best_of(py + [pyc], 1)
    py_valid = n_py / wall
    print("python scorer, Draft202012Validator:     %8.0f episodes/s  (%d files)" % (py_valid, n_py))
    print("ratio a3rig (2 threads, validating) / python (validating):   %.0fx" % (results[2] / py_valid))
    print("ratio a3rig (2 threads, validating) / python (no validation): %.1fx" % (results[2] / py_plain))

    n_huge = sum(1 for _ in glob.iglob(os.path.join(huge, "*", "*", "*", "*.json")))
    rss_big = peak_rss_mib([a3rig, "score", "-q", "--format", "csv", big])
    rss_huge = peak_rss_mib([a3rig, "score", "-q", "--format", "csv", huge])
    print("peak memory: %.1f MiB for %d files, %.1f MiB for %d files" % (rss_big, n_big, rss_huge, n_huge))
    if not args.work:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
