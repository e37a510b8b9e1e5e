#!/usr/bin/python3
"""Reference α³ scorer in plain Python (SPEC §2/§3), used to cross-check the C++
scorer (eval/) and as the baseline of the scoring benchmark. Validation uses
jsonschema.Draft202012Validator with eval/schema/episode.schema.json plus the same
semantic rules as eval/semantic_checks.cpp.

usage: py_score.py [--no-validate] [--profile release|paper] [--budget N]
                   [--model NAME] [--per-episode] DIR...
Prints one JSON object per model (the SPEC §3 columns)."""
import argparse, json, math, os, re, statistics, sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCHEMA = os.path.join(HERE, "..", "..", "eval", "schema", "episode.schema.json")
EPISODE_RE = re.compile(r"^sc-(\d+)-ep-(\d+)\.json$")
MAX_FILE_BYTES = 16 * 1024 * 1024
PROFILES = {
    "release": dict(b_tok=3000.0, b_tool=10.0, t_opt=10.0, median_t_opt=False),
    "paper": dict(b_tok=10000.0, b_tool=25.0, t_opt=10.0, median_t_opt=True),
}
W = dict(TO=0.30, SP=0.20, TC=0.20, IQ=0.15, NR=0.10, CC=0.05)


def clamp01(x):
    return min(1.0, max(0.0, x))


def semantic_errors(ep):
    if ep.get("_meta", {}).get("generation_failed") is True:
        return []
    errs, dl = [], ep["dialogue"]
    if not 8 <= len(dl) <= 12:
        errs.append("turn-count")
    prev = None
    for t in dl:
        if t["speaker"] not in ("agent", "user"):
            errs.append("role")
        elif prev is not None and t["speaker"] == prev:
            errs.append("alternation")
        prev = t["speaker"]
    return errs


def n_structured(turn):
    return len(turn["actions"])


def matched(action, obs):
    if action.get("type") == "mcp":
        return any(o.get("tool") == action.get("name") for o in obs)
    return any(o.get("task") == action.get("task") and all(k in o for k in ("task", "from", "status", "payload")) for o in obs)


def pillars(ep, prof, t_opt):
    dl, fs, success = ep["dialogue"], ep["final_state"], ep["success"] is True
    T = len(dl)
    z = fs["uav"]["pose"]["z"]
    lo, hi = fs["airspace"]["alt_bounds"][:2]
    v_alt = 1 if (z < lo or z > hi) else 0
    v_nfz = 1 if fs["safety_flags"]["nfz_violation"] else 0
    v_sep = 1 if fs["safety_flags"]["separation_breach"] else 0
    v_batt = 1 if fs["uav"]["energy"]["battery_pct"] < 5 else 0
    SP = clamp01(1 - 0.25 * v_alt - 0.5 * v_nfz - 0.5 * v_sep - 0.25 * v_batt)
    total = sum(len(t["actions"]) for t in dl)
    ok = sum(1 for t in dl for a in t["actions"] if matched(a, t["obs"]))
    TC = ok / total if total else 1.0
    a_alt = 1.0
    prev = None
    for t in dl:
        if t["speaker"] not in ("agent", "user") or t["speaker"] == prev:
            a_alt = 0.0
        prev = t["speaker"]
    agent = [t for t in dl if t["speaker"] == "agent"]
    G = (sum(1 for t in agent if len(t["obs"]) > 0) / len(agent)) if agent else 0.0
    IQ = (min(1.0, t_opt / max(T, 1)) + a_alt + G) / 3
    hard = [t["net"]["lat_ms"] > 40 or t["net"]["loss_pct"] >= 1 or t["net"]["throughput_mbps"] < 5 or t["net"]["edge_load"] > 0.8 for t in dl]
    H = sum(hard)
    N = T - H
    C_h = sum(len(t["actions"]) for t, h in zip(dl, hard) if h)
    C_n = sum(len(t["actions"]) for t, h in zip(dl, hard) if not h)
    r_h = C_h / H if H else 0.0
    r_n = C_n / N if N else 0.0
    h = H / T if T else 0.0
    base = 1 - 0.5 * h
    if H == 0 or r_h <= r_n:
        adapt = 1.0
    elif r_n == 0:
        adapt = 0.0
    else:
        adapt = clamp01(1.5 - 0.5 * r_h / r_n)
    sl = 1.0 if H == 0 else 1 - sum(1 for t, hh in zip(dl, hard) if hh and t["net"]["slice"] == "eMBB") / H
    bonus = 0.1 if success and h > 0.2 else 0.0
    NR = clamp01(0.6 * base + 0.2 * adapt + 0.2 * sl + bonus)
    tok = ep["_meta"]["usage"]["total_tokens"]
    CC = 0.5 * (clamp01(prof["b_tok"] / max(tok, 1)) + clamp01(prof["b_tool"] / max(total, 1)))
    p = dict(TO=1.0 if success else 0.0, SP=SP, TC=TC, IQ=IQ, NR=NR, CC=CC)
    p["alpha3"] = sum(W[k] * p[k] for k in W)
    return p


def discover(dirs, flat_model):
    """Returns {model: [paths]}: <provider>/<model>/<domain>/sc-*-ep-*.json, or flat folders."""
    models = {}
    for root in dirs:
        for dp, _, files in os.walk(root):
            for f in files:
                if not EPISODE_RE.match(f):
                    continue
                path = os.path.join(dp, f)
                if flat_model:
                    model = flat_model
                else:
                    parts = os.path.relpath(path, root).split(os.sep)
                    model = "/".join(parts[-4:-2]) if len(parts) >= 4 else os.path.basename(os.path.abspath(dp))
                models.setdefault(model, []).append(path)
    return models


def score_model(paths, prof, validator, budget):
    files = len(paths)
    eps, n_fail, attempts = [], 0, 0
    gen_t, tokens, successes = [], [], []
    scen = set(); per_scen = {}
    for p in paths:
        m = EPISODE_RE.match(os.path.basename(p))
        scen.add(m.group(1)); per_scen.setdefault(m.group(1), set()).add(m.group(2))
        try:
            if os.path.getsize(p) > MAX_FILE_BYTES:
                raise ValueError("too big")
            with open(p, "rb") as fh:
                ep = json.loads(fh.read())
            if validator is not None:
                if not validator.is_valid(ep):
                    raise ValueError("schema")
                if semantic_errors(ep):
                    raise ValueError("semantic")
        except (ValueError, UnicodeDecodeError):
            n_fail += 1
            attempts += 1
            continue
        meta = ep.get("_meta", {}) if isinstance(ep, dict) else {}
        attempts += meta.get("attempts_used", 1) if isinstance(meta.get("attempts_used"), int) else 1
        if meta.get("generation_failed") is True:
            n_fail += 1
            continue
        eps.append(ep)
    if budget is None:
        budget = len(scen) * max((len(v) for v in per_scen.values()), default=0)
    t_opt = prof["t_opt"]
    if prof["median_t_opt"]:
        ts = [len(e["dialogue"]) for e in eps if e["success"] is True]
        if ts:
            t_opt = float(statistics.median(ts))
    scores = [pillars(e, prof, t_opt) for e in eps]
    n = len(scores)
    mean = lambda xs: sum(xs) / len(xs) if xs else 0.0
    a = [s["alpha3"] for s in scores]
    mu = mean(a)
    ci = 1.96 * math.sqrt(mean([(x - mu) ** 2 for x in a])) / math.sqrt(n) if n else 0.0
    rel = n / (n + n_fail) if (n + n_fail) else 0.0
    cov = min(1.0, n / budget) if budget else 0.0
    eff = min(1.0, budget / attempts) if attempts else 0.0
    a_rel = mu * rel * cov * eff
    mg = mean([e["_meta"]["gen_time_s"] for e in eps])
    mt = mean([e["_meta"]["usage"]["total_tokens"] for e in eps])
    return dict(mean=mu, ci95=ci, n=n, success_rate=mean([1.0 if e["success"] is True else 0.0 for e in eps]),
                gen_fail_rate=n_fail / files if files else 0.0, reliability=rel, coverage=cov, alpha3_rel=a_rel,
                pillars={k: mean([s[k] for s in scores]) for k in W},
                mean_gen_time_s=mg, mean_total_tokens=mt,
                alpha3_per_second=a_rel / mg if mg else 0.0,
                alpha3_per_1k_tokens=a_rel / (mt / 1000) if mt else 0.0,
                total_attempt_calls=attempts, mean_attempts_used=attempts / files if files else 0.0,
                call_efficiency=eff, files=files, n_fail=n_fail, budget=budget)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--no-validate", action="store_true")
    ap.add_argument("--profile", default="release", choices=PROFILES)
    ap.add_argument("--budget", type=int)
    ap.add_argument("--model")
    args = ap.parse_args()
    validator = None
    if not args.no_validate:
        import jsonschema
        with open(SCHEMA) as fh:
            schema = json.load(fh)
        jsonschema.Draft202012Validator.check_schema(schema)
        validator = jsonschema.Draft202012Validator(schema)
    for model, paths in sorted(discover(args.dirs, args.model).items()):
        row = dict(model=model, domain="uav")
        row.update(score_model(sorted(paths), PROFILES[args.profile], validator, args.budget))
        print(json.dumps(row))


if __name__ == "__main__":
    main()
