#!/usr/bin/env python3
"""Independent reference for docs/stability.md ("The SPP's location error"): each SPP of a result file of `spp solve`
re-solved in 60-digit mpmath from the system's physical first-order flows (paper eqs. 3.9-3.11; no spp code), and its
Floquet spectral radius from the full monodromy exp(2 t1 A1) exp(2 t2 A2) Pi (largest modulus but the structural
1, 1, 0, 0: at 60 digits the Jordan pair at 1 splits by ~1e-30 only, so a third multiplier within 1e-11 of 1 is told
apart). Unknowns: the mid-contact position y (velocity 0 there) and t1, t2; equations: w^T y + g0 = 0, zero contact
force at the release t2 later, zero velocity at mid-flight t1 after that.

  floquet_fold_reference.py SYSTEM.json RESULT.json     (~40 s per SPP for n = 5)

On tests/data/chain5_k5_fold.json (`spp solve ... --t1-min 7.6 --t1-max 7.7 --t2-min 10.45 --t2-max 10.55 --json`):
the SPP is 7.1e-11 away in t1 and t2, residual 2e-60, rho - 1 = +1.526e-11.
"""
import json, sys
import mpmath as mp

def load(path):
    d = json.load(open(path))
    return mp.matrix(d["M"]), mp.matrix(d["K"]), mp.matrix(d["w"]), mp.mpf(d["g0"])

def setup(M, K, w):
    n = M.rows
    Mi = M ** -1
    b2 = (w.T * Mi * w)[0]
    kt = (w.T * Mi * K) / b2          # force row: lambda(x) = kt x
    Kt = K - w * kt                    # K~ (eq. 2.4)
    A1 = mp.zeros(2 * n); A2 = mp.zeros(2 * n)
    for i in range(n):
        A1[i, n + i] = 1; A2[i, n + i] = 1
    MK, MKt = -Mi * K, -Mi * Kt
    for i in range(n):
        for j in range(n):
            A1[n + i, j] = MK[i, j]; A2[n + i, j] = MKt[i, j]
    P = mp.eye(n) - Mi * w * w.T / b2
    Pi = mp.zeros(2 * n)
    for i in range(n):
        for j in range(n):
            Pi[i, j] = P[i, j]; Pi[n + i, n + j] = P[i, j]
    return A1, A2, Pi, kt

def residual(M, K, w, g0, A1, A2, kt, y, t1, t2):
    """Mid-contact state (y, 0): gap closed, force zero at release (t2 later), zero velocity at mid-flight."""
    n = M.rows
    X = mp.matrix(2 * n, 1)
    for i in range(n): X[i] = y[i]
    Xr = mp.expm(t2 * A2) * X
    Xf = mp.expm(t1 * A1) * Xr
    F = [(w.T * y)[0] + g0, (kt * Xr[0:n, 0])[0]] + [Xf[n + i] for i in range(n)]
    return F, Xr

def solve(path, t1, t2, x0, v0, dps=60):
    mp.mp.dps = dps
    M, K, w, g0 = load(path)
    n = M.rows
    A1, A2, Pi, kt = setup(M, K, w)
    X0 = mp.matrix([mp.mpf(v) for v in x0] + [mp.mpf(v) for v in v0])
    Xm = mp.expm(mp.mpf(t2) * A2) * X0     # mid-contact from the onset
    z = [Xm[i] for i in range(n)] + [mp.mpf(t1), mp.mpf(t2)]
    def G(*zz):
        F, _ = residual(M, K, w, g0, A1, A2, kt, mp.matrix(zz[:n]), zz[n], zz[n + 1])
        return F
    for it in range(30):  # Newton, central-difference Jacobian at 1e-(dps/2)
        F = mp.matrix(G(*z))
        if mp.norm(F) < mp.mpf(10) ** (-dps + 8): break
        h = mp.mpf(10) ** (-dps // 2)
        J = mp.matrix(n + 2, n + 2)
        for j in range(n + 2):
            zp = list(z); zm = list(z); zp[j] += h; zm[j] -= h
            Fp, Fm = G(*zp), G(*zm)
            for i in range(n + 2): J[i, j] = (Fp[i] - Fm[i]) / (2 * h)
        dz = mp.lu_solve(J, -F)
        z = [z[i] + dz[i] for i in range(n + 2)]
    t1s, t2s = z[n], z[n + 1]
    res = mp.norm(mp.matrix(G(*z)))
    mono = mp.expm(2 * t1s * A1) * mp.expm(2 * t2s * A2) * Pi
    ev = mp.eig(mono, left=False, right=False)
    ev = sorted(ev, key=lambda e: abs(e - 1))
    rest = sorted(ev[2:], key=lambda e: abs(e))[2:]      # drop the structural 1, 1 and 0, 0
    rho = max(abs(e) for e in rest)
    return t1s, t2s, rho, res, min(abs(e) for e in ev[2:]), abs(ev[0]-1), abs(ev[1]-1)

if __name__ == "__main__":
    sol = json.load(open(sys.argv[2]))
    for s in sol["solutions"]:
        t1s, t2s, rho, res, zmin, s0, s1 = solve(sys.argv[1], s["t1"], s["t2"], s["x0"], s["v0"])
        f = s.get("stability", s)
        print("t1 %.17g t2 %.17g | true t1 %s t2 %s (dt %.3g %.3g) residual %.2g" % (s["t1"], s["t2"], mp.nstr(t1s, 20), mp.nstr(t2s, 20), float(t1s - s["t1"]), float(t2s - s["t2"]), float(res)))
        print("   true rho - 1 = %.4g   (zero mults %.2g, split %.2g %.2g)" % (float(rho - 1), float(zmin), float(s0), float(s1)))
