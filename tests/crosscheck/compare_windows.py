#!/usr/bin/python3
"""Completeness cross-check of `spp solve` against the independent brute force (brute_force.py).

    python3 compare_windows.py [--seed S] [--cases N] [--outdir DIR] [--tiling-cases T] [--max-n 8]

For the paper's chain5 and rod4 and for random systems generated from the seed (n = 2..8; dense random SPD M
and K, random unit w, g0 = 1; "stiff" variants whose stiffness eigenvalues spread over 1e5), random windows
(from the default lower ends, and windows away from the axes), it runs the spp CLI (env SPP_CLI, default
build/spp) and the brute force on the same window and reports
  * roots of the brute force that spp misses, roots of spp the brute force does not have (match: every
    |t_i - t_i'| <= 1e-7 |t_i|), spp's status, admissibility disagreements (informational);
  * tiling: the window split into 2..6 random tiles, spp run on each, union compared with the whole window.
Roots within 1e-7 (relative) of a window edge are listed apart ("edge"), not counted as disagreements.
Every system is saved in --outdir with the command lines that reproduce each disagreement.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import brute_force as bf  # noqa: E402  (sets the BLAS thread variables before numpy is imported)
import numpy as np  # noqa: E402

SRC = os.path.dirname(os.path.dirname(HERE))
CLI = os.environ.get("SPP_CLI", os.path.join(SRC, "build", "spp"))
TOL = 1e-7
EXAMPLES = os.path.join(SRC, "examples")


# ------------------------------------------------------------------------------------------ systems
def _spd(n, rng):
    A = rng.standard_normal((n, n))
    S = A @ A.T / n + 0.3 * np.eye(n)
    return (S + S.T) / 2


def random_system(n, rng, stiff=False):
    M = _spd(n, rng)
    if stiff:
        Q = np.linalg.qr(rng.standard_normal((n, n)))[0]
        lam = 10 ** rng.uniform(0, 5, n)
        lam[0], lam[-1] = 1.0, 1e5
        K = (Q * lam) @ Q.T
        K = (K + K.T) / 2
    else:
        K = _spd(n, rng)
    w = rng.standard_normal(n)
    w /= np.linalg.norm(w)
    return {"name": f"random{'_stiff' if stiff else ''}_n{n}", "M": M.tolist(), "K": K.tolist(),
            "w": w.tolist(), "g0": 1.0}


def load_example(name):
    with open(os.path.join(EXAMPLES, name)) as f:
        return json.load(f)


def scales(system):
    sy = bf.SPPSystem(system["M"], system["K"], system["w"], system["g0"])
    return sy.q1, sy.q2, bf.default_lower(sy)


def random_window(rng, system, kind=None):
    """kind 'origin': from the default lower ends; 'offset': away from both axes; 'offset_t1' / 'offset_t2':
    away from one axis only. Sizes in quarter periods pi/(2 f_max) of each phase."""
    q1, q2, (d1, d2) = scales(system)
    kind = kind or rng.choice(["origin", "offset", "offset_t1", "offset_t2"])
    a1, a2 = rng.uniform(0.5, 12) * q1, rng.uniform(0.5, 12) * q2
    w = [a1, a1 + rng.uniform(0.5, 5) * q1, a2, a2 + rng.uniform(0.5, 5) * q2]
    if kind in ("origin", "offset_t2"):
        w[0], w[1] = d1, rng.uniform(2, 14) * q1
    if kind in ("origin", "offset_t1"):
        w[2], w[3] = d2, rng.uniform(2, 14) * q2
    return w


def window_kind(window, system):
    _, _, (d1, d2) = scales(system)
    o1, o2 = window[0] > 1.5 * d1, window[2] > 1.5 * d2
    return {(False, False): "origin", (True, True): "offset", (True, False): "offset_t1",
            (False, True): "offset_t2"}[(o1, o2)]


# ------------------------------------------------------------------------------------------ runs
def _fmt(x):
    return repr(float(x))


def spp_command(system_path, window, out):
    a1, b1, a2, b2 = window
    return [CLI, "solve", system_path, "--t1-min", _fmt(a1), "--t1-max", _fmt(b1), "--t2-min", _fmt(a2),
            "--t2-max", _fmt(b2), "--json", out, "--quiet"]


def brute_command(system_path, window):
    return ["/usr/bin/python3", os.path.join(HERE, "brute_force.py"), system_path, "--window",
            *map(_fmt, window)]


def run_spp(system_path, window):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "r.json")
        cmd = spp_command(system_path, window, out)
        t0 = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True)
        dt = time.time() - t0
        if p.returncode != 0 or not os.path.exists(out):
            return {"status": f"exit {p.returncode}: {(p.stderr or p.stdout).strip()[:200]}", "solutions": [],
                    "seconds": dt}
        with open(out) as f:
            r = json.load(f)
    return {"status": r.get("status"), "solutions": r.get("solutions", []), "seconds": dt,
            "warnings": r.get("warnings", [])}


def run_brute(system, window):
    t0 = time.time()
    r = bf.solve(system, *window)
    r["seconds"] = time.time() - t0
    return r


def _match(r, others):
    for s in others:
        if abs(s["t1"] - r["t1"]) <= TOL * abs(r["t1"]) and abs(s["t2"] - r["t2"]) <= TOL * abs(r["t2"]):
            return s
    return None


def _near_edge(r, window):
    a1, b1, a2, b2 = window
    return any(abs(r["t1"] - e) <= TOL * max(abs(e), abs(r["t1"])) for e in (a1, b1)) or \
        any(abs(r["t2"] - e) <= TOL * max(abs(e), abs(r["t2"])) for e in (a2, b2))


def compare(ref, other, window):
    """roots of ref missing in other, roots of other not in ref (edge roots apart)."""
    missing, extra, edge = [], [], []
    for r in ref:
        if _match(r, other) is None:
            (edge if _near_edge(r, window) else missing).append(r)
    for s in other:
        if _match(s, ref) is None:
            (edge if _near_edge(s, window) else extra).append(s)
    return missing, extra, edge


def _pts(rs):
    return [(round(r["t1"], 10), round(r["t2"], 10)) for r in rs]


def run_case(name, system, window, workdir, tiles=None, rng=None):
    """one comparison; returns a record with the disagreements and the commands to reproduce them."""
    path = os.path.join(workdir, f"{name}.json")
    with open(path, "w") as f:
        json.dump(system, f)
    bfr = run_brute(system, window)
    sp = run_spp(path, window)
    missing, extra, edge = compare(bfr["roots"], sp["solutions"], window)
    unresolved = [e for e in extra if _match(e, bfr["rejected"]) is not None]   # rounding-level onset roots
    extra = [e for e in extra if _match(e, bfr["rejected"]) is None]
    adm = []
    for r in bfr["roots"]:
        s = _match(r, sp["solutions"])
        if s is not None and bool(s.get("admissible")) != bool(r["admissible"]):
            adm.append((r["t1"], r["t2"], r["admissible"], s.get("admissible"), r["min_gap_rel"],
                        r["min_force_rel"]))
    extra_diag = [diagnose_extra(system, e) for e in extra]
    rec = {"name": name, "n": len(system["w"]), "window": window, "kind": window_kind(window, system),
           "brute": len(bfr["roots"]),
           "spp": len(sp["solutions"]), "spp_status": sp["status"], "missing_in_spp": _pts(missing),
           "extra_in_spp": _pts(extra), "extra_diagnosis": extra_diag, "edge": _pts(edge),
           "spp_has_brute_unresolved": _pts(unresolved), "brute_unresolved": _pts(bfr["rejected"]),
           "admissibility_mismatch": adm,
           "brute_certified": bfr["stats"]["certified"], "brute_warnings": bfr["warnings"],
           "brute_unverified": [(r["t1"], r["t2"]) for r in bfr["roots"] if not r["verified"]],
           "brute_seconds": bfr["seconds"], "spp_seconds": sp["seconds"],
           "spp_cmd": " ".join(spp_command(path, window, "OUT.json")),
           "brute_cmd": " ".join(brute_command(path, window))}
    if tiles:
        rec["tiling"] = tiling(path, window, sp, bfr, tiles, rng or np.random.default_rng(0))
    return rec


def diagnose_extra(system, s):
    """a root of spp that the brute force does not have: the paper's residuals at it, and the brute force
    rerun in a small window around it (roots there = the brute force sees a root nearby after all)."""
    sy = bf.SPPSystem(system["M"], system["K"], system["w"], system["g0"])
    v = bf.verify(sy, s["t1"], s["t2"])
    t1, t2 = s["t1"], s["t2"]
    w = [0.5 * t1, min(1.5 * t1, t1 + 0.05 * sy.q1), max(0.5 * t2, t2 - 0.05 * sy.q2), t2 + 0.05 * sy.q2]
    loc = bf.solve(system, *w, verify_roots=False)
    return {"t1": t1, "t2": t2, "spp_flags": s.get("flags"), "spp_residual": s.get("residual"),
            "onset_rel_at_spp_root": v["onset_rel"], "t1_over_quarter_period": t1 / sy.q1,
            "local_window": w, "local_brute_roots": [(r["t1"], r["t2"]) for r in loc["roots"]],
            "local_certified": loc["stats"]["certified"]}


def split_window(window, ntiles, rng):
    """ntiles (2..6) tiles as a k1 x k2 grid of random cuts."""
    shapes = [(k1, k2) for k1 in range(1, 7) for k2 in range(1, 7) if k1 * k2 == ntiles]
    k1, k2 = shapes[rng.integers(len(shapes))]
    a1, b1, a2, b2 = window
    c1 = np.r_[a1, np.sort(rng.uniform(a1, b1, k1 - 1)), b1]
    c2 = np.r_[a2, np.sort(rng.uniform(a2, b2, k2 - 1)), b2]
    return [[c1[i], c1[i + 1], c2[j], c2[j + 1]] for i in range(k1) for j in range(k2)]


def tiling(path, window, whole, bfr, ntiles, rng):
    tiles = split_window(window, ntiles, rng)
    union, statuses, cmds = [], [], []
    for t in tiles:
        r = run_spp(path, t)
        statuses.append(r["status"])
        union += r["solutions"]
        cmds.append(" ".join(spp_command(path, t, "OUT.json")))
    cuts = [e for t in tiles for e in t]
    def near_cut(r):
        return any(abs(r["t1"] - e) <= TOL * max(abs(e), abs(r["t1"])) for e in cuts) or \
            any(abs(r["t2"] - e) <= TOL * max(abs(e), abs(r["t2"])) for e in cuts)
    m_w, x_w, _ = compare(whole["solutions"], union, window)
    m_b, x_b, _ = compare(bfr["roots"], union, window)
    x_b = [e for e in x_b if _match(e, bfr["rejected"]) is None]
    dup = len(union) - len({(round(s["t1"], 9), round(s["t2"], 9)) for s in union})
    return {"tiles": tiles, "statuses": statuses, "union": len(union), "duplicates": dup,
            "whole_not_in_union": _pts([r for r in m_w if not near_cut(r)]),
            "union_not_in_whole": _pts([r for r in x_w if not near_cut(r)]),
            "brute_not_in_union": _pts([r for r in m_b if not near_cut(r)]),
            "union_not_in_brute": _pts([r for r in x_b if not near_cut(r)]),
            "near_cut": _pts([r for r in m_w + x_w + m_b + x_b if near_cut(r)]), "cmds": cmds}


def disagrees(rec):
    bad = bool(rec["missing_in_spp"] or rec["extra_in_spp"] or rec["spp_status"] != "success")
    t = rec.get("tiling")
    if t:
        bad |= bool(t["whole_not_in_union"] or t["union_not_in_whole"] or t["brute_not_in_union"]
                    or t["union_not_in_brute"] or t["duplicates"] or any(s != "success" for s in t["statuses"]))
    return bad


# ------------------------------------------------------------------------------------------ cases
def make_cases(seed, ncases, max_n=8, stiff_every=4):
    """(name, system, window) list: chain5 and rod4 fixed windows, then random systems and windows."""
    rng = np.random.default_rng(seed)
    c5, r4 = load_example("chain5.json"), load_example("rod4.json")
    cases = [("chain5_paper_window", c5, [3.1, 3.3, 0.45, 0.6]),
             ("chain5_origin", c5, [scales(c5)[2][0], 12.0, scales(c5)[2][1], 12.0]),
             ("chain5_random", c5, random_window(rng, c5, "offset")),
             ("rod4_origin", r4, [scales(r4)[2][0], 8.0, scales(r4)[2][1], 3.0]),
             ("rod4_random", r4, random_window(rng, r4, "offset"))]
    for k in range(ncases):
        n = int(rng.integers(2, max_n + 1))
        stiff = stiff_every and k % stiff_every == stiff_every - 1
        system = random_system(n, rng, stiff=stiff)
        cases.append((f"s{seed}_c{k}_{system['name']}", system, random_window(rng, system)))
    return cases, rng


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=20, help="random cases (after the 5 chain5/rod4 cases)")
    ap.add_argument("--max-n", type=int, default=8)
    ap.add_argument("--tiling-cases", type=int, default=6, help="how many cases also get a tiling check")
    ap.add_argument("--outdir", default=os.path.join(tempfile.gettempdir(), "spp_crosscheck"))
    ap.add_argument("--json", help="write all records here")
    a = ap.parse_args(argv)
    os.makedirs(a.outdir, exist_ok=True)
    cases, rng = make_cases(a.seed, a.cases, a.max_n)
    tiled = set(rng.choice(len(cases), size=min(a.tiling_cases, len(cases)), replace=False).tolist())
    recs = []
    print(f"spp: {CLI}; systems in {a.outdir}")
    for i, (name, system, window) in enumerate(cases):
        rec = run_case(name, system, window, a.outdir, tiles=int(rng.integers(2, 7)) if i in tiled else None,
                       rng=rng)
        recs.append(rec)
        flag = "DISAGREE" if disagrees(rec) else "ok"
        w = ", ".join(f"{x:.6g}" for x in window)
        print(f"[{flag:8}] {name:34} n={rec['n']} window=({w}) brute={rec['brute']} spp={rec['spp']} "
              f"status={rec['spp_status']} missing_in_spp={len(rec['missing_in_spp'])} "
              f"extra_in_spp={len(rec['extra_in_spp'])} t_brute={rec['brute_seconds']:.2f}s "
              f"t_spp={rec['spp_seconds']:.2f}s" + (" tiled" if "tiling" in rec else ""), flush=True)
        if not rec["brute_certified"] or rec["brute_unverified"]:
            print(f"           brute force NOT certified/verified: {rec['brute_warnings']} {rec['brute_unverified']}")
    print("\n=== disagreements ===")
    for rec in recs:
        if not disagrees(rec) and not rec["admissibility_mismatch"]:
            continue
        print(f"--- {rec['name']} (n={rec['n']}, spp status {rec['spp_status']})")
        print(f"    spp:   {rec['spp_cmd']}")
        print(f"    brute: {rec['brute_cmd']}")
        if rec["missing_in_spp"]:
            print(f"    missing in spp ({len(rec['missing_in_spp'])}): {rec['missing_in_spp'][:12]}")
        if rec["extra_in_spp"]:
            print(f"    extra in spp ({len(rec['extra_in_spp'])}): {rec['extra_in_spp'][:12]}")
            for d in rec["extra_diagnosis"]:
                print(f"      ({d['t1']:.10g}, {d['t2']:.10g}): spp flags {d['spp_flags']}, t1 = "
                      f"{d['t1_over_quarter_period']:.2g} quarter periods, onset residual there "
                      f"{d['onset_rel_at_spp_root']:.1e}; brute force around it: {d['local_brute_roots']}")
        if rec["edge"]:
            print(f"    (at a window edge, ignored: {rec['edge']})")
        if rec["admissibility_mismatch"]:
            print(f"    admissibility differs (t1, t2, brute, spp, min_gap_rel, min_force_rel): "
                  f"{rec['admissibility_mismatch']}")
        t = rec.get("tiling")
        if t and disagrees({**rec, "missing_in_spp": [], "extra_in_spp": [], "spp_status": "success"}):
            print(f"    tiling into {len(t['tiles'])}: statuses {t['statuses']}, duplicates {t['duplicates']}")
            for k in ("whole_not_in_union", "union_not_in_whole", "brute_not_in_union", "union_not_in_brute"):
                if t[k]:
                    print(f"      {k} ({len(t[k])}): {t[k][:12]}")
            for c in t["cmds"]:
                print(f"      {c}")
    print("\n=== by window kind ===")
    for kind in ("origin", "offset_t1", "offset_t2", "offset"):
        rs = [r for r in recs if r["kind"] == kind]
        if rs:
            print(f"{kind:10} {len(rs):3d} cases: {sum(bool(r['missing_in_spp']) for r in rs)} with roots missing in "
                  f"spp ({sum(len(r['missing_in_spp']) for r in rs)} roots), "
                  f"{sum(bool(r['extra_in_spp']) for r in rs)} with extra roots in spp, "
                  f"{sum(r['spp_status'] != 'success' for r in rs)} not 'success'")
    tl = [r["tiling"] for r in recs if "tiling" in r]
    if tl:
        print(f"tiling    {len(tl):3d} cases: {sum(bool(t['whole_not_in_union']) for t in tl)} where the union of the tiles "
              f"misses roots of the whole window, {sum(bool(t['union_not_in_whole']) for t in tl)} where it has more, "
              f"{sum(bool(t['duplicates']) for t in tl)} with duplicates")
    print(f"brute force: {sum(not r['brute_certified'] for r in recs)} runs not certified, "
          f"{sum(len(r['brute_unverified']) for r in recs)} roots failing verification; "
          f"time per case median {np.median([r['brute_seconds'] for r in recs]):.2f} s, "
          f"max {max(r['brute_seconds'] for r in recs):.2f} s")
    nbad = sum(disagrees(r) for r in recs)
    print(f"\n{nbad} of {len(recs)} cases disagree; brute force total {sum(r['brute_seconds'] for r in recs):.1f} s")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(recs, f, indent=1, default=str)
    return 1 if nbad else 0


if __name__ == "__main__":
    sys.exit(main())
