#!/usr/bin/env python3
"""Issue 14: the Floquet bound under an ill-conditioned mass matrix (docs/stability.md, "The modal form's error").

  floquet_conditioning.py make SYSTEM.json OUT.json --cond C [--seed S]
      writes SYSTEM in the coordinates x = T y, T = U diag(logspace(0, log10 C, n)) V^T with U, V orthogonal from
      numpy's default_rng(S) (S = 1 by default): M' = T^T M T, K' = T^T K T (symmetrised), w' = T^T w, g0 unchanged.
      cond(T) = C, cond(M') ~ C^2 cond(M). The multipliers are invariant: only the rounding changes.
  floquet_conditioning.py check SYSTEM.json RESULT.json [--dps D]
      each SPP of a `spp solve --json` result re-solved in D-digit mpmath (40 by default) from the system's physical
      first-order flows (paper eqs. 3.9-3.11; no spp code): unknowns the mid-contact position y and t1, t2, equations
      w^T y + g0 = 0, zero contact force at the release, zero velocity at mid-flight (Newton, analytic Jacobian). Its
      radius: the largest modulus of exp(2 t1 A1) exp(2 t2 A2) Pi but the structural 1, 1 (nearest 1) and 0, 0.
      Prints |rho - rho_true| against spectral_radius_error and the verdict against the truth; the last line counts
      the SPPs outside their bound and the contradicted verdicts.

Measured (docs/stability.md): chain5 in (0, 12]^2 with C = 1e3 and C = 1e4, before and after the modal form's error
entered the bound.
"""
import json
import sys

import mpmath as mp


def make(args):
    import numpy as np
    src, out = args[0], args[1]
    cond = float(args[args.index("--cond") + 1])
    seed = int(args[args.index("--seed") + 1]) if "--seed" in args else 1
    s = json.load(open(src))
    M, K, w = np.array(s["M"], float), np.array(s["K"], float), np.array(s["w"], float)
    n = len(w)
    rng = np.random.default_rng(seed)
    U, _ = np.linalg.qr(rng.standard_normal((n, n)))
    V, _ = np.linalg.qr(rng.standard_normal((n, n)))
    T = U @ np.diag(np.logspace(0, np.log10(cond), n)) @ V.T
    Mp, Kp = T.T @ M @ T, T.T @ K @ T
    json.dump({"name": "%s_dense_cond%g_seed%d" % (s.get("name", "system"), cond, seed),
               "M": ((Mp + Mp.T) / 2).tolist(), "K": ((Kp + Kp.T) / 2).tolist(), "w": (T.T @ w).tolist(),
               "g0": float(s["g0"])}, open(out, "w"), indent=1)
    print("cond(T) %.3g, cond(M') %.3g" % (np.linalg.cond(T), np.linalg.cond(Mp)))


class Reference:
    def __init__(self, path):
        s = json.load(open(path))
        self.M = mp.matrix([[mp.mpf(float(v)) for v in r] for r in s["M"]])
        self.K = mp.matrix([[mp.mpf(float(v)) for v in r] for r in s["K"]])
        self.w = mp.matrix([mp.mpf(float(v)) for v in s["w"]])
        self.g0 = mp.mpf(float(s["g0"]))
        n = self.n = self.M.rows
        Mi = mp.inverse(self.M)
        Miw = Mi * self.w
        b2 = (self.w.T * Miw)[0]
        MK = Mi * self.K
        self.k = (self.w.T * MK) / b2  # contact force row: lambda(x) = k x (eq. 2.7)
        MKt = MK - Miw * self.k
        self.A1, self.A2, self.Pi = mp.zeros(2 * n), mp.zeros(2 * n), mp.zeros(2 * n)
        P = mp.eye(n) - Miw * self.w.T / b2
        for i in range(n):
            self.A1[i, n + i] = self.A2[i, n + i] = 1
            for j in range(n):
                self.A1[n + i, j], self.A2[n + i, j] = -MK[i, j], -MKt[i, j]
                self.Pi[i, j] = self.Pi[n + i, n + j] = P[i, j]

    def equations(self, z):
        n = self.n
        X = mp.matrix(2 * n, 1)
        for i in range(n):
            X[i] = z[i]
        E2, E1 = mp.expm(self.A2 * z[n + 1]), mp.expm(self.A1 * z[n])
        Xr = E2 * X
        Xm = E1 * Xr
        F = mp.matrix(n + 2, 1)
        F[0] = sum(self.w[i] * z[i] for i in range(n)) + self.g0
        F[1] = sum(self.k[0, i] * Xr[i] for i in range(n))
        J = mp.zeros(n + 2, n + 2)
        E12 = E1 * E2
        dXm1, dXr2 = self.A1 * Xm, self.A2 * Xr
        dXm2 = E1 * dXr2
        for i in range(n):
            F[2 + i] = Xm[n + i]
            J[0, i] = self.w[i]
            J[1, i] = sum(self.k[0, j] * E2[j, i] for j in range(n))
            for j in range(n):
                J[2 + j, i] = E12[n + j, i]
            J[2 + i, n], J[2 + i, n + 1] = dXm1[n + i], dXm2[n + i]
        J[1, n + 1] = sum(self.k[0, i] * dXr2[i] for i in range(n))
        return F, J

    def spp(self, t1, t2, x0, v0):
        n = self.n
        X0 = mp.matrix([mp.mpf(v) for v in list(x0) + list(v0)])
        Xc = mp.expm(self.A2 * mp.mpf(t2)) * X0  # mid-contact, from the onset
        z = mp.matrix([Xc[i] for i in range(n)] + [mp.mpf(t1), mp.mpf(t2)])
        for _ in range(30):
            F, J = self.equations(z)
            if mp.norm(F) < mp.mpf(10) ** (-(mp.mp.dps - 8)):
                break
            z = z - mp.lu_solve(J, F)
        F, _ = self.equations(z)
        t1s, t2s = z[n], z[n + 1]
        mono = mp.expm(self.A1 * (2 * t1s)) * mp.expm(self.A2 * (2 * t2s)) * self.Pi
        ev = sorted(mp.eig(mono, left=False, right=False), key=lambda e: abs(e))[2:]  # the structural 0, 0
        ev = sorted(ev, key=lambda e: abs(e - 1))[2:]  # the structural 1, 1
        return t1s, t2s, max([abs(e) for e in ev] or [mp.mpf(0)]), mp.norm(F)


def check(args):
    dps = int(args[args.index("--dps") + 1]) if "--dps" in args else 40
    mp.mp.dps = dps
    ref = Reference(args[0])
    sols = json.load(open(args[1]))["solutions"]
    print("#   t1 t2 adm verdict | rho err | rho_true | |diff| diff/err | dt1 dt2 | residual")
    outside = contradicted = checked = 0
    worst = 0.0
    for i, s in enumerate(sols):
        if s.get("spectral_radius") is None or not s.get("floquet_multipliers"):
            continue
        t1s, t2s, rho, res = ref.spp(s["t1"], s["t2"], s["x0"], s["v0"])
        rc, err, verdict = s["spectral_radius"], s["spectral_radius_error"], s["stability_verdict"]
        err = float("inf") if err is None else err
        diff = float(abs(rho - mp.mpf(rc)))
        ratio = diff / err if err > 0 else (0.0 if diff == 0 else float("inf"))
        flag = ""
        if ratio > 1:
            outside += 1
            flag += " OUTSIDE-BOUND"
        if (verdict == "stable" and rho >= 1) or (verdict == "unstable" and rho <= 1):
            contradicted += 1
            flag += " WRONG-VERDICT"
        checked += 1
        worst = max(worst, ratio)
        print("%3d %.10g %.10g %d %-9s | %.15f %.2e | %s | %.2e %.3g | %.1e %.1e | %s%s" % (
            i, s["t1"], s["t2"], int(s["admissible"]), verdict, rc, err, mp.nstr(rho, 18), diff, ratio,
            float(t1s - mp.mpf(s["t1"])), float(t2s - mp.mpf(s["t2"])), mp.nstr(res, 3), flag), flush=True)
    print("%d SPPs checked: %d outside their bound, %d verdicts contradicted, worst error / bound %.3g" % (
        checked, outside, contradicted, worst))
    return 1 if outside or contradicted else 0


if __name__ == "__main__":
    if len(sys.argv) < 4 or sys.argv[1] not in ("make", "check"):
        sys.exit(__doc__)
    sys.exit(make(sys.argv[2:]) if sys.argv[1] == "make" else check(sys.argv[2:]))
