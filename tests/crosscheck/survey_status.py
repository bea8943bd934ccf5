"""Status survey (not a test): `SPP_CLI=build/spp /usr/bin/python3 tests/crosscheck/survey_status.py random|stiff7|chains
[extra solve flags, e.g. --no-certify-steps]` solves 35 random dense systems n = 2..8 (every third stiff, spread 1e5)
in 8 x 8 quarter periods from the axes, 40 random stiff 7-dof systems (spread 1e5) in the same windows, or six
random-mass 10-dof chains in their fundamental box (chain20: one 20-dof chain, seed 20), and prints each status, root count and the counted causes.
Results go to /tmp/survey."""
import json, subprocess, sys, os, numpy as np, time
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_windows as cw
CLI = os.environ.get("SPP_CLI", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "spp"))
out = "/tmp/survey"
os.makedirs(out, exist_ok=True)
def chain(n, rng):
    m = rng.uniform(0.5, 2, n)
    K = np.zeros((n, n))
    for i in range(n):
        K[i, i] = 2 if i < n - 1 else 1
        if i + 1 < n: K[i, i+1] = K[i+1, i] = -1
    w = np.zeros(n); w[-1] = -1
    return {"name": f"rchain{n}", "M": np.diag(m).tolist(), "K": K.tolist(), "w": w.tolist(), "g0": 1.0}
def run(sy, window, tag):
    p = f"{out}/{tag}.json"; json.dump(sy, open(p, "w"))
    r = f"{out}/{tag}_res.json"
    a1, b1, a2, b2 = window
    cmd = [CLI, "solve", p, "--t1-max", repr(b1), "--t2-max", repr(b2), "--json", r, "--quiet"] + sys.argv[2:]
    if a1 is not None: cmd += ["--t1-min", repr(a1), "--t2-min", repr(a2)]
    t = time.time(); cp = subprocess.run(cmd, capture_output=True, text=True); dt = time.time() - t
    line = (cp.stdout.strip().splitlines() or [""])[-1]
    try:
        res = json.load(open(r)); st = res.get("stats", {})
        keys = ["evaluations","certified_steps","heuristic_steps","uncertified_steps","uncertified_corners","unpaired_crossings","unresolved_pieces","unpolished_roots"]
        print(f"{tag:24s} {res['status']:10s} roots={len(res['solutions']):5d} {dt:6.1f}s", " ".join(f"{k[:10]}={st.get(k)}" for k in keys if st.get(k)), flush=True)
    except Exception as e:
        print(tag, "ERR", cp.returncode, cp.stderr[-300:], flush=True)
mode = sys.argv[1]
if mode == "chains":
    for seed in range(1, 7):
        rng = np.random.default_rng(seed)
        sy = chain(10, rng)
        bf = cw.bf.SPPSystem(sy["M"], sy["K"], sy["w"], sy["g0"])
        om = bf.om
        w1 = om.min(); d = np.sort(bf.dpos)
        run(sy, [None, np.pi / w1, None, np.pi / d[0]], f"rchain10_s{seed}")
elif mode == "chain20":  # one random-mass 20-dof chain (seed 20) in its fundamental box: a long run (~1 h here)
    rng = np.random.default_rng(20)
    sy = chain(20, rng)
    bf = cw.bf.SPPSystem(sy["M"], sy["K"], sy["w"], sy["g0"])
    run(sy, [None, np.pi / bf.om.min(), None, np.pi / np.sort(bf.dpos)[0]], "rchain20_s20")
elif mode == "random":
    for seed in range(1, 36):
        rng = np.random.default_rng(1000 + seed)
        n = int(rng.integers(2, 9)); stiff = seed % 3 == 0
        sy = cw.random_system(n, rng, stiff)
        q1, q2, (d1, d2) = cw.scales(sy)
        run(sy, [None, 8 * q1, None, 8 * q2], f"rand{seed}_n{n}{'s' if stiff else ''}")
elif mode == "stiff7":
    for seed in range(40):
        rng = np.random.default_rng(7000 + seed)
        sy = cw.random_system(7, rng, True)
        q1, q2, _ = cw.scales(sy)
        run(sy, [None, 8 * q1, None, 8 * q2], f"stiff7_{seed}")
