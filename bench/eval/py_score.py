#!/usr/bin/python3
"""Reference α³ scorer in plain Python (SPEC §2/§3), used to cross-check the C++
scorer (eval/) and as the baseline of the scoring benchmark. Validation uses
jsonschema.Draft202012Validator with eval/schema/episode.schema.json plus the same
semantic rules as eval/episode_document.cpp.

usage: py_score.py [--no-validate] [--profile release|paper] [--budget N]
                   [--model NAME] [--domain NAME] [--per-episode FILE.jsonl] DIR...
Prints one JSON object per model (the SPEC §3 columns), best alpha3_rel first.
Same conventions as `a3rig score`: model = the last three folders of a file's path
(provider/model/domain), the default budget = scenarios found x episode numbers found,
the paper profile's T_opt = median T of the run's valid successful episodes."""
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


def refers(o, a):
    """An observation refers to an action when it names the action's tool (MCP) or task (A2A)."""
    if a["type"] == "mcp":
        return isinstance(o.get("tool"), str) and o["tool"] == a["name"]
    return isinstance(o.get("task"), str) and o["task"] == a["task"]


def semantic_errors(ep):
    """The rules JSON Schema does not express (eval/episode_document.hpp)."""
    if ep.get("_meta", {}).get("generation_failed") is True:
        return []
    errs, dl = [], ep["dialogue"]
    if not 8 <= len(dl) <= 12:
        errs.append("turn-count")
    prev = None
    for t in dl:
        if t["speaker"] not in ("agent", "user"):
            errs.append("role")
        elif t["speaker"] == prev:
            errs.append("alternation")
        prev = t["speaker"]
        for o in t["obs"]:
            if "tool" not in o and "task" not in o:
                errs.append("observation-fields")
        for a in t["actions"]:
            need = ("name", "args") if a["type"] == "mcp" else ("task", "to", "payload")
            if any(k not in a for k in need):
                errs.append("action-fields")
            elif not any(refers(o, a) for o in t["obs"]):
                errs.append("unanswered-action")
    return errs


def matched(action, obs):
    """TC's match: an A2A answer must also carry from, status and payload."""
    if action.get("type") == "mcp":
        return any(refers(o, action) for o in obs)
    return any(refers(o, action) and all(k in o for k in ("task", "from", "status", "payload")) for o in obs)


def landed_at_home(ep):
    """final_state.uav.landed.site == "home", on the ground, within 15 m of the initial pose."""
    uav, home = ep["final_state"]["uav"], ep["initial_state"]["uav"]["pose"]
    landed, pose = uav.get("landed"), uav["pose"]
    return (isinstance(landed, dict) and landed.get("site") == "home" and abs(pose["z"]) <= 1.0
            and math.hypot(pose["x"] - home["x"], pose["y"] - home["y"]) <= 15.0)


def pillars(ep, prof, t_opt):
    dl, fs, success = ep["dialogue"], ep["final_state"], ep["success"] is True
    T = len(dl)
    z = fs["uav"]["pose"]["z"]
    lo, hi = fs["airspace"]["alt_bounds"][:2]
    v_alt = 1 if (z < lo or z > hi) else 0
    if v_alt and landed_at_home(ep):  # a3rig's checked landing marker (eval/README.md)
        v_alt = 0
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


def summarize(a, budget):
    eps, scores, files, n_fail, attempts = a["eps"], a["scores"], a["files"], a["n_fail"], a["attempts"]
    n = len(scores)
    mean = lambda xs: sum(xs) / len(xs) if xs else 0.0
    al = [s["alpha3"] for s in scores]
    mu = mean(al)
    ci = 1.96 * math.sqrt(mean([(x - mu) ** 2 for x in al])) / math.sqrt(n) if n else 0.0
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


def discover(dirs, flat_model, flat_domain):
    """Yields (model, domain, path, scenario, episode) in sorted order."""
    for root in dirs:
        if os.path.isfile(root):
            candidates = [root]
        else:
            candidates = []
            for dp, dns, files in os.walk(root):
                dns.sort()
                candidates += [os.path.join(dp, f) for f in sorted(files) if EPISODE_RE.match(f)]
        for path in candidates:
            m = EPISODE_RE.match(os.path.basename(path))
            if flat_model:
                model, domain = flat_model, flat_domain
            else:
                parts = os.path.abspath(path).split(os.sep)
                domain, model = parts[-2], "/".join(p for p in parts[-4:-2] if p)
            yield model, domain, path, (m.group(1) if m else None), (m.group(2) if m else None)


def load(path, validator):
    """Returns (status, episode or None, attempts); status is valid, failure_stub or invalid."""
    attempts = 1
    try:
        if os.path.getsize(path) > MAX_FILE_BYTES:
            return "invalid", None, 1
        with open(path, "rb") as fh:
            ep = json.loads(fh.read())
    except (ValueError, UnicodeDecodeError, OSError):
        return "invalid", None, 1
    if isinstance(ep, dict) and isinstance(ep.get("_meta"), dict):
        a = ep["_meta"].get("attempts_used")
        if isinstance(a, (int, float)) and not isinstance(a, bool) and a >= 1 and a == int(a):
            attempts = int(a)
    if validator is not None and not validator.is_valid(ep):
        return "invalid", None, attempts
    if ep["_meta"].get("generation_failed") is True:
        return "failure_stub", None, attempts
    if validator is not None and semantic_errors(ep):
        return "invalid", None, attempts
    return "valid", ep, attempts


def median_t_opt(args, validator):
    ts = []
    for _, _, path, _, _ in discover(args.dirs, args.model, args.domain):
        status, ep, _ = load(path, validator)
        if status == "valid" and ep["success"] is True:
            ts.append(len(ep["dialogue"]))
    return float(statistics.median(ts)) if ts else 10.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--no-validate", action="store_true")
    ap.add_argument("--profile", default="release", choices=PROFILES)
    ap.add_argument("--budget", type=int)
    ap.add_argument("--model")
    ap.add_argument("--domain", default="uav")
    ap.add_argument("--per-episode")
    args = ap.parse_args()
    validator = None
    if not args.no_validate:
        import jsonschema
        with open(SCHEMA) as fh:
            schema = json.load(fh)
        jsonschema.Draft202012Validator.check_schema(schema)
        validator = jsonschema.Draft202012Validator(schema)
    prof = PROFILES[args.profile]
    t_opt = median_t_opt(args, validator) if prof["median_t_opt"] else prof["t_opt"]
    per_ep = open(args.per_episode, "w") if args.per_episode else None
    acc, scen, epis = {}, set(), set()
    for model, domain, path, sc, epn in discover(args.dirs, args.model, args.domain):
        if sc is not None:
            scen.add(int(sc))
            epis.add(int(epn))
        a = acc.setdefault((model, domain), dict(files=0, n_fail=0, attempts=0, eps=[], scores=[]))
        status, ep, attempts = load(path, validator)
        a["files"] += 1
        a["attempts"] += attempts
        row = dict(file=path, status=status)
        if status == "valid":
            p = pillars(ep, prof, t_opt)
            a["eps"].append(ep)
            a["scores"].append(p)
            row.update(p)
        else:
            a["n_fail"] += 1
        if per_ep:
            per_ep.write(json.dumps(row) + "\n")
    budget = args.budget if args.budget else (len(scen) * len(epis) or sum(a["files"] for a in acc.values()))
    rows = []
    for (model, domain), a in acc.items():
        row = dict(model=model, domain=domain)
        row.update(summarize(a, budget))
        rows.append(row)
    rows.sort(key=lambda r: (-r["alpha3_rel"], -r["mean"]))
    for row in rows:
        print(json.dumps(row))


if __name__ == "__main__":
    main()
