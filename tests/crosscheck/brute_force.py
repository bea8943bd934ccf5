#!/usr/bin/python3
"""Independent finder of every SPP (paper: Thorin, Delezoide, Legrand 2017) whose half-durations lie in a window.

    python3 brute_force.py SYSTEM.json --window T1MIN T1MAX T2MIN T2MAX [--grid N] [--json OUT]

Written from the paper alone (not from spp's solver), in physical coordinates x:

  flight   M x'' + K x = 0,   x'' = -B x,   B = M^-1 K
  contact  M x'' + K~ x = 0,  x'' = -B~ x,  B~ = M^-1 K~,  K~ = (I - w w^T M^-1 / (w^T M^-1 w)) K   (eq. 2.4)

With (x0, v0) the state at contact onset (t = 0), flight on [-2 t1, 0], contact on [0, 2 t2], an axially
symmetric SPP (Theorem 3.1) has zero velocity at mid-flight and at mid-contact:

  v(-t1) = S(B, t1) x0 + C(B, t1) v0 = 0,   v(t2) = -S(B~, t2) x0 + C(B~, t2) v0 = 0,

C(A, t) = cos(t sqrt(A)), S(A, t) = sqrt(A) sin(t sqrt(A)) (entire functions of A: no square-root or pole issue).
This is R(t1, t2) z = 0 with z = (x0, v0); R is the paper's R2 (eq. 5.1a) in x instead of y = M^1/2 x, so
det R = det R2. Zero onset acceleration (eq. 5.1b) is a(z) = w^T M^-1 K x0 = 0; the gap closure w^T x0 = -g0
fixes the scale (needs p0 = w^T x0 != 0). All matrix functions come from eigen-decompositions of the physical
B and B~.

Method (complete by construction up to rounding; not a grid search):
  1. Exact root count on any segment of a line t1 = const or t2 = const, by inertia. Away from the poles of
     tan, det R = prod cos(t1 om_i) prod cos(t2 d_j) det H with, in the K-orthonormal flight modal coordinates,
     H(t1, t2) = diag(om tan(t1 om)) + U diag(d tan(t2 d)) U^T (symmetric; U d^2 U^T is B~ in those coordinates;
     om, d: flight and contact frequencies). dH/dt1 is positive definite, dH/dt2 positive semi-definite, so the
     eigenvalues of H only increase: #roots of det R in (a, b] = neg(a) - neg(b) + #poles of tan in (a, b]
     (Wittrick-Williams). Roots on the window edges are isolated by bisection on this count, then Brent on det R.
     (det R and this form are checked against each other at start-up.)
  2. Since H increases in t1 and t2, every curve det R = 0 is a non-increasing graph t1 = f(t2) and curves never
     cross (generically): no closed loop, and each curve crosses the window in one arc that enters through the
     left edge (t2 = T2MIN) or the top edge (t1 = T1MAX). Every arc is traced from its entry by pseudo-arclength
     continuation on (t1, t2, z), R z = 0, |z| = 1, z = (B^1/2 x0, v0) oriented continuously, with steps bounded
     (0.5 / f_max in time, 0.2 rad of rotation of z). A step is refused if it jumps to another curve: the number
     of curves below the point on its line t2 = const plus those that left through the bottom edge is constant
     along an arc, and is checked exactly (step 1) at every step.
  3. Certification: the trace lands on every line of a grid (N lines per quarter period pi/(2 f_max) of each
     phase, capped at 400); the landings on every grid segment must equal the exact count of step 1 and the exits
     the roots isolated on the downstream edges, else everything is retraced with smaller steps (and the run
     says certified=False if that still fails).
  4. Along each arc the onset condition a(z) is a smooth signed function: each sign change between steps is
     solved on the arc (Brent in s = t2 - t1, which increases along every arc); each step where the cubic Hermite
     interpolant of a (values and slopes from the tangents) dips towards zero, and each sampled local minimum of
     |a|, is searched for a close pair or a double root; then Newton on the full system (t1, t2, z): R z = 0,
     a(z) = 0, z_ref^T z = 1. A root whose sign change is below the rounding noise of a (next to the t1 -> 0 axis,
     where a ~ t1^2) is listed as rejected, not as a root.
  5. Each root is checked with the paper's own residuals (R2 built from L1, L2 of section 3 in y = M^1/2 x,
     eqs. 5.1a-b), by propagating (x0, v0) of eq. 5.2 over one period with scipy.linalg.expm of the two physical
     first-order systems (return error in the energy norm), and its admissibility (ineqs. 5.3) is sampled densely
     (>= 400 samples per period of the fastest mode, then refined).
"""
import argparse
import json
import math
import os
import sys
import time

for _v in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")   # tiny matrices: threads only cost time
import numpy as np  # noqa: E402
import scipy.linalg as sla  # noqa: E402
from scipy.optimize import brentq, minimize_scalar  # noqa: E402

PI = math.pi


class SPPSystem:
    def __init__(self, M, K, w, g0):
        M = np.array(M, dtype=float)
        K = np.array(K, dtype=float)
        w = np.array(w, dtype=float)
        nw = np.linalg.norm(w)
        if nw == 0:
            raise ValueError("w = 0")
        w, g0 = w / nw, float(g0) / nw
        self.M, self.K, self.w, self.g0 = M, K, w, g0
        n = self.n = len(w)
        if n < 2:
            raise ValueError("n >= 2 needed (with n = 1 the contact phase has no oscillating mode)")
        self.N = 2 * n
        I = np.eye(n)
        # --- flight: generalized symmetric eigenproblem K phi = omega^2 M phi, Phi^T M Phi = I
        om2, Phi = sla.eigh(K, M)
        if om2.min() <= 0:
            raise ValueError("K not positive definite")
        self.om = np.sqrt(om2)
        self.lam1 = om2
        self.V1, self.V1i = Phi, Phi.T @ M          # B = V1 diag(om2) V1i
        # --- contact: K~ of eq. (2.4), B~ = M^-1 K~ = P K with P symmetric PSD
        Minv_w = np.linalg.solve(M, w)
        c = w @ Minv_w
        self.Kt = (I - np.outer(w, Minv_w) / c) @ K
        self.B = np.linalg.solve(M, K)
        self.Bt = np.linalg.solve(M, self.Kt)
        P = self.Bt @ np.linalg.inv(K)
        if np.linalg.norm(P - P.T) > 1e-8 * np.linalg.norm(P):
            raise RuntimeError("M^-1 K~ K^-1 not symmetric: K~ wrong")
        P = (P + P.T) / 2
        Lk = np.linalg.cholesky(K)                  # K = Lk Lk^T, B~ ~ Lk^T P Lk (symmetric PSD)
        S = Lk.T @ P @ Lk
        lam2, Wv = np.linalg.eigh((S + S.T) / 2)
        lam2 = np.where(lam2 < 1e-13 * lam2.max(), 0.0, lam2)
        self.lam2 = lam2
        self.d = np.sqrt(lam2)
        self.V2 = sla.solve_triangular(Lk.T, Wv, lower=False)
        self.V2i = Wv.T @ Lk.T                     # B~ = V2 diag(lam2) V2i
        if np.linalg.norm((self.V2 * lam2) @ self.V2i - self.Bt) > 1e-9 * np.linalg.norm(self.Bt):
            raise RuntimeError("eigen-decomposition of B~ inaccurate")
        self.dpos = self.d[self.d > 0]
        # energy scaling of the unknown: z = (B^1/2 x0, v0), B^1/2 = V1 diag(om) V1i
        self.Bh = (self.V1 * self.om) @ self.V1i
        self.Bhi = (self.V1 / self.om) @ self.V1i
        # onset functional: a = w^T M^-1 K x0
        self.ell = K @ Minv_w
        self.wr = max(self.om.max(), self.d.max())  # time scale of the continuation variables wr t
        self.q1 = PI / (2 * self.om.max())          # quarter periods of the fastest flight / contact modes
        self.q2 = PI / (2 * self.d.max())
        el = self.Bhi.T @ self.ell
        self.ellz = np.r_[el / np.linalg.norm(el), np.zeros(n)]   # a(z) up to a positive factor
        # --- symmetric form for the inertia count (K-orthonormal flight modal coordinates r = Omega Phi^-1 x)
        bm = Phi.T @ w
        Sr = self.om[:, None] * (I - np.outer(bm, bm) / (bm @ bm)) * self.om[None, :]
        dc2, self.U = np.linalg.eigh((Sr + Sr.T) / 2)
        self.dc = np.sqrt(np.clip(dc2, 0, None))
        self.dc[self.dc < 1e-6 * self.dc.max()] = 0.0
        if np.max(np.abs(np.sort(self.dc) - np.sort(self.d))) > 1e-7 * self.d.max():
            raise RuntimeError("modal and physical contact frequencies disagree")
        self._self_check()

    # ---------------------------------------------------------------- physical R and its derivatives
    def Rhat(self, t1, t2, deriv=False):
        """R acting on z = (B^1/2 x0, v0): rows v(-t1) and v(t2)."""
        n = self.n
        th1 = t1 * self.om
        th2 = t2 * self.d
        C1 = (self.V1 * np.cos(th1)) @ self.V1i
        S1 = (self.V1 * (self.om * np.sin(th1))) @ self.V1i
        C2 = (self.V2 * np.cos(th2)) @ self.V2i
        S2 = (self.V2 * (self.d * np.sin(th2))) @ self.V2i
        R = np.empty((2 * n, 2 * n))
        R[:n, :n], R[:n, n:], R[n:, :n], R[n:, n:] = S1 @ self.Bhi, C1, -S2 @ self.Bhi, C2
        if not deriv:
            return R
        dS1 = (self.V1 * (self.lam1 * np.cos(th1))) @ self.V1i
        dS2 = (self.V2 * (self.lam2 * np.cos(th2))) @ self.V2i
        R1 = np.zeros_like(R)
        R2 = np.zeros_like(R)
        R1[:n, :n], R1[:n, n:] = dS1 @ self.Bhi, -S1
        R2[n:, :n], R2[n:, n:] = -dS2 @ self.Bhi, -S2
        return R, R1, R2

    def detR(self, t1, t2):
        return np.linalg.det(self.Rhat(t1, t2))

    # ---------------------------------------------------------------- inertia count
    def H(self, t1, t2):
        Hc = (self.U * (self.dc * np.tan(t2 * self.dc))) @ self.U.T
        return Hc + np.diag(self.om * np.tan(t1 * self.om))

    def neg(self, t1, t2):
        return int(np.sum(np.linalg.eigvalsh(self.H(t1, t2)) < 0))

    def neg_grid(self, t1s, t2s):
        t1s, t2s = np.asarray(t1s), np.asarray(t2s)
        n = self.n
        Hc = np.einsum("ik,tk,jk->tij", self.U, self.dc[None, :] * np.tan(np.outer(t2s, self.dc)), self.U)
        Hf = self.om[None, :] * np.tan(np.outer(t1s, self.om))
        out = np.empty((len(t1s), len(t2s)), dtype=int)
        idx = np.arange(n)
        chunk = max(1, 200000 // max(1, len(t2s) * n * n))
        for a in range(0, len(t1s), chunk):
            Hb = np.repeat(Hc[None], min(chunk, len(t1s) - a), axis=0)
            Hb[..., idx, idx] += Hf[a:a + chunk, None, :]
            out[a:a + chunk] = np.sum(np.linalg.eigvalsh(Hb) < 0, axis=-1)
        return out

    @staticmethod
    def npoles(freqs, a, b):
        """number of poles (k + 1/2) pi / f, k >= 0, in (a, b] (a, b >= 0), summed over f."""
        return int(np.sum(np.floor(b * freqs / PI - 0.5) - np.floor(a * freqs / PI - 0.5)))

    @staticmethod
    def off_pole(t, freqs, direction, eps=1e-6):
        """move t (in `direction`) until it is at least eps * pi / f from every pole of tan(t f)."""
        for _ in range(1000):
            ph = t * freqs / PI - 0.5
            k = np.round(ph)
            bad = np.abs(ph - k) < eps
            if not bad.any():
                return t
            i = int(np.argmax(bad))
            t = (k[i] + 0.5 + direction * 2 * eps) * PI / freqs[i]
        return t

    def _self_check(self):
        rng = np.random.default_rng(1)
        for _ in range(6):
            t1, t2 = rng.uniform(0.1, 3) * self.q1, rng.uniform(0.1, 3) * self.q2
            lhs = np.linalg.det(self.Rhat(t1, t2)) * np.prod(self.om)
            rhs = np.prod(np.cos(t1 * self.om)) * np.prod(np.cos(t2 * self.d)) * np.linalg.det(self.H(t1, t2))
            if abs(lhs - rhs) > 1e-6 * max(abs(lhs), abs(rhs)) + 1e-10 * np.prod(self.wr + self.om):
                raise RuntimeError(f"det R and its inertia form disagree: {lhs} vs {rhs}")

    # ---------------------------------------------------------------- continuation
    def correct(self, x, zref, cvec, cval, maxit=10):
        """Newton on R z = 0, zref.z = 1, cvec.x = cval, x = (wr t1, wr t2, z)."""
        N, wr = self.N, self.wr
        x = x.copy()
        J = np.zeros((N + 2, N + 2))
        for it in range(maxit):
            R, R1, R2 = self.Rhat(x[0] / wr, x[1] / wr, deriv=True)
            z = x[2:]
            F = np.r_[R @ z, zref @ z - 1.0, cvec @ x - cval]
            J[:N, 0], J[:N, 1], J[:N, 2:] = R1 @ z / wr, R2 @ z / wr, R
            J[N, :] = 0
            J[N, 2:] = zref
            J[N + 1, :] = cvec
            try:
                dx = np.linalg.solve(J, -F)
            except np.linalg.LinAlgError:
                return x, it, False
            x += dx
            if np.linalg.norm(dx) < 1e-10 * (1 + np.linalg.norm(x[:2])):
                x[2:] /= np.linalg.norm(x[2:])
                return x, it + 1, True
        x[2:] /= np.linalg.norm(x[2:])
        return x, maxit, False

    def tangent(self, x):
        N, wr = self.N, self.wr
        R, R1, R2 = self.Rhat(x[0] / wr, x[1] / wr, deriv=True)
        z = x[2:]
        J = np.zeros((N + 1, N + 2))
        J[:N, 0], J[:N, 1], J[:N, 2:] = R1 @ z / wr, R2 @ z / wr, R
        J[N, 2:] = z
        v = np.linalg.svd(J)[2][-1]
        return v if v[1] - v[0] > 0 else -v

    def null_vector(self, t1, t2):
        return np.linalg.svd(self.Rhat(t1, t2))[2][-1]

    def onset(self, x):
        return float(self.ellz @ x[2:])


def _brent(g, lo, hi):
    """root of g in [lo, hi] (g(lo), g(hi) of opposite signs up to rounding)."""
    glo, ghi = g(lo), g(hi)
    if glo == 0 or ghi == 0 or glo * ghi > 0:
        return lo if abs(glo) <= abs(ghi) else hi
    return brentq(g, lo, hi, xtol=1e-14 * max(1.0, abs(lo)), maxiter=200)


class Finder:
    def __init__(self, sysm, t1min, t1max, t2min, t2max, grid=2, cap=400, hmax=0.5, amax=0.2):
        self.s = s = sysm
        self.win = (t1min, t1max, t2min, t2max)
        self.hmax, self.amax = hmax, amax
        self.warnings = []
        self.near_tangencies = []          # (t1, t2, min |a|) of dips of the onset condition that miss zero
        # enlarged window with edges off the poles (roots outside the true window are filtered at the end)
        T1lo = s.off_pole(t1min * (1 - 1e-9), s.om, -1)
        T1hi = s.off_pole(t1max * (1 + 1e-9), s.om, +1)
        T2lo = s.off_pole(t2min * (1 - 1e-9), s.dpos, -1) if len(s.dpos) else t2min
        T2hi = s.off_pole(t2max * (1 + 1e-9), s.dpos, +1) if len(s.dpos) else t2max
        if T1lo <= 0 or T2lo <= 0:
            raise ValueError("window lower ends must be > 0")

        def lines(lo, hi, q, freqs):
            k = int(min(cap, max(1, math.ceil((hi - lo) / (q / grid)))))
            v = np.linspace(lo, hi, k + 1)
            v[1:-1] = [s.off_pole(t, freqs, +1) for t in v[1:-1]]
            v = np.unique(v)
            return v[(v >= lo) & (v <= hi)]

        self.L1 = lines(T1lo, T1hi, s.q1, s.om)        # horizontal lines t1 = L1[i]
        self.L2 = lines(T2lo, T2hi, s.q2, s.dpos)      # vertical lines t2 = L2[j]
        self.negs = s.neg_grid(self.L1, self.L2)
        self.stats = {"grid": [len(self.L1), len(self.L2)], "arcs": 0, "steps": 0, "landings": 0,
                      "retraces": 0, "newton_failures": 0, "jumps_caught": 0,
                      "dips_examined": 0}

    # exact roots of det R on the edge lines
    def edge_roots(self, kind, idx):
        sy = self.s
        if kind == "h":        # t1 = L1[idx] fixed, u = t2
            us, negs, freqs = self.L2, self.negs[idx, :], sy.dpos
            val = self.L1[idx]
            pt = lambda u: (val, u)
        else:                  # t2 = L2[idx] fixed, u = t1
            us, negs, freqs = self.L1, self.negs[:, idx], sy.om
            val = self.L2[idx]
            pt = lambda u: (u, val)
        roots = []

        def cnt(a, b, na, nb):
            return na - nb + sy.npoles(freqs, a, b)

        def isolate(a, b, na, nb, Z):
            if Z == 1:
                f = lambda u: sy.detR(*pt(u))
                fa, fb = f(a), f(b)
                if fa * fb < 0:
                    roots.append((brentq(f, a, b, xtol=1e-15 * max(1.0, b), rtol=4 * np.finfo(float).eps,
                                         maxiter=200), 1))
                else:
                    self.warnings.append(f"edge {kind}{idx}: count 1 but no sign change of det R in ({a}, {b})")
                    roots.append(((a + b) / 2, 1))
                return
            if b - a < 1e-13 * max(1.0, b):
                self.warnings.append(f"edge {kind}{idx}: {Z} roots within ({a}, {b})")
                roots.extend([((a + b) / 2, 1)] * Z)
                return
            m = sy.off_pole((a + b) / 2, freqs, +1, eps=1e-9) if len(freqs) else (a + b) / 2
            if not a < m < b:
                m = sy.off_pole((a + b) / 2, freqs, -1, eps=1e-9)
            nm = sy.neg(*pt(m))
            Z1 = cnt(a, m, na, nm)
            if Z1 < 0 or Z1 > Z:
                self.warnings.append(f"edge {kind}{idx}: inconsistent inertia count in ({a}, {b})")
                Z1 = max(0, min(Z, Z1))
            if Z1:
                isolate(a, m, na, nm, Z1)
            if Z - Z1:
                isolate(m, b, nm, nb, Z - Z1)

        for k in range(len(us) - 1):
            Z = cnt(us[k], us[k + 1], negs[k], negs[k + 1])
            if Z < 0:
                self.warnings.append(f"edge {kind}{idx}: negative count on ({us[k]}, {us[k + 1]}]")
            elif Z > 0:
                isolate(us[k], us[k + 1], negs[k], negs[k + 1], Z)
        return [pt(u) for u, _ in roots]

    def segment_counts(self):
        """exact number of roots of det R on each grid segment: (horizontal lines, vertical lines)."""
        sy = self.s
        h = np.zeros((len(self.L1), len(self.L2) - 1), dtype=int)
        v = np.zeros((len(self.L1) - 1, len(self.L2)), dtype=int)
        for j in range(len(self.L2) - 1):
            h[:, j] = self.negs[:, j] - self.negs[:, j + 1] + sy.npoles(sy.dpos, self.L2[j], self.L2[j + 1])
        for i in range(len(self.L1) - 1):
            v[i, :] = self.negs[i, :] - self.negs[i + 1, :] + sy.npoles(sy.om, self.L1[i], self.L1[i + 1])
        return h, v

    # ------------------------------------------------------------ trace one arc from its entry
    def below(self, t1, t2):
        """number of roots of det R on the line t2 = const strictly between the bottom edge and t1 (exact count),
        or None when the count would be unreliable (t1 too close to the bottom edge or a point near a pole)."""
        sy = self.s
        t = t1 * (1 - 1e-9)
        if t <= self.L1[0] * (1 + 1e-9) or np.min(np.abs(np.cos(t * sy.om))) < 1e-7 or \
                (len(sy.dpos) and np.min(np.abs(np.cos(t2 * sy.dpos))) < 1e-7):
            return None
        return sy.neg(self.L1[0], t2) - sy.neg(t, t2) + sy.npoles(sy.om, self.L1[0], t)

    def label(self, t1, t2):
        """constant along an arc: curves below it on a vertical line + those that left through the bottom edge
        before (curves are non-increasing graphs t1 = f(t2) that never cross)."""
        b = self.below(t1, t2)
        return None if b is None else b + int(np.searchsorted(self.bottom_exits, t2, side="right"))

    def trace(self, t1, t2, start_line, hmax, amax):
        sy, wr = self.s, self.s.wr
        N = sy.N
        z = sy.null_vector(t1, t2)
        x = np.r_[wr * t1, wr * t2, z]
        x, _, ok = sy.correct(x, z, np.r_[(1.0, 0.0) if start_line[0] == "h" else (0.0, 1.0), np.zeros(N)],
                              x[0] if start_line[0] == "h" else x[1])
        lab = self.label(t1, t2)
        pts = [x]
        v = sy.tangent(x)
        tans = [v]
        land = [start_line]
        done = {start_line}
        h = min(hmax, 0.1)
        L1w, L2w = self.L1 * wr, self.L2 * wr
        for _ in range(200000):
            xp = x + h * v
            y, it, ok = sy.correct(xp, x[2:], v, v @ xp)
            ang = math.acos(min(1.0, abs(float(x[2:] @ y[2:]))))
            bad = not ok or ang > amax or np.linalg.norm(y - xp) > 0.3 * h or (y[1] - y[0]) <= (x[1] - x[0])
            if not bad and lab is not None:
                ly = self.label(y[0] / wr, y[1] / wr)
                if ly is not None and ly != lab:
                    bad = True                       # the corrector jumped to another curve
                    self.stats["jumps_caught"] += 1
            if bad:
                h *= 0.5
                if h < 1e-12:
                    raise RuntimeError(f"continuation stalled at t = {x[:2] / wr}")
                continue
            if lab is None:
                lab = self.label(y[0] / wr, y[1] / wr)
            self.stats["steps"] += 1
            # first grid line crossed between x and y
            best = None
            lo, hi = min(x[0], y[0]), max(x[0], y[0])
            for i in np.nonzero((L1w > lo) & (L1w < hi))[0]:
                if ("h", i) not in done:
                    f = (L1w[i] - x[0]) / (y[0] - x[0])
                    if best is None or f < best[0]:
                        best = (f, ("h", int(i)))
            lo, hi = min(x[1], y[1]), max(x[1], y[1])
            for j in np.nonzero((L2w > lo) & (L2w < hi))[0]:
                if ("v", j) not in done:
                    f = (L2w[j] - x[1]) / (y[1] - x[1])
                    if best is None or f < best[0]:
                        best = (f, ("v", int(j)))
            if y[0] > self.L1[-1] * wr or y[1] < self.L2[0] * wr:
                raise RuntimeError("arc left the window through an entry edge")
            if best is not None:
                f, line = best
                cvec = np.zeros(N + 2)
                if line[0] == "h":
                    cvec[0], cval = 1.0, L1w[line[1]]
                else:
                    cvec[1], cval = 1.0, L2w[line[1]]
                yl, it, ok = sy.correct(x + f * (y - x), x[2:], cvec, cval)
                ang = math.acos(min(1.0, abs(float(x[2:] @ yl[2:]))))
                bad = not ok or ang > amax or (yl[1] - yl[0]) <= (x[1] - x[0]) or \
                    (yl[1] - yl[0]) > (y[1] - y[0]) + 1e-12
                if not bad and lab is not None:
                    ly = self.label(yl[0] / wr, yl[1] / wr)
                    if ly is not None and ly != lab:
                        bad = True
                        self.stats["jumps_caught"] += 1
                if bad:
                    h *= 0.5
                    if h < 1e-12:
                        raise RuntimeError(f"landing stalled at t = {x[:2] / wr}")
                    continue
                yl[0 if line[0] == "h" else 1] = cval
                x = yl
                done.add(line)
                land.append(line)
                self.stats["landings"] += 1
                pts.append(x)
                v = sy.tangent(x)
                tans.append(v)
                if (line[0] == "h" and line[1] == 0) or (line[0] == "v" and line[1] == len(self.L2) - 1):
                    break
            else:
                x = y
                land.append(None)
                pts.append(x)
                v = sy.tangent(x)
                tans.append(v)
            if it <= 3 and ang < amax / 3:
                h = min(1.6 * h, hmax)
        else:
            raise RuntimeError("arc too long")
        return np.array(pts), land, np.array(tans)

    def trace_all(self):
        sy = self.s
        entries = [(p, ("v", 0)) for p in self.edge_roots("v", 0)]
        entries += [(p, ("h", len(self.L1) - 1)) for p in self.edge_roots("h", len(self.L1) - 1)]
        exits = [(p, ("h", 0)) for p in self.edge_roots("h", 0)]
        exits += [(p, ("v", len(self.L2) - 1)) for p in self.edge_roots("v", len(self.L2) - 1)]
        self.bottom_exits = np.sort([p[1] for p, l in exits if l == ("h", 0)])
        self.stats["entries"], self.stats["exits"] = len(entries), len(exits)
        hc, vc = self.segment_counts()
        hmax, amax = self.hmax, self.amax
        for attempt in range(4):
            arcs, problems = [], []
            hl = np.zeros_like(hc)
            vl = np.zeros_like(vc)
            exit_pts = []
            for p, line in entries:
                try:
                    pts, land, tans = self.trace(p[0], p[1], line, hmax, amax)
                except RuntimeError as e:
                    problems.append(f"trace from {p}: {e}")
                    continue
                arcs.append((pts, land, tans))
                for x, l in zip(pts, land):
                    if l is None or l == line:
                        continue
                    t1, t2 = x[0] / sy.wr, x[1] / sy.wr
                    if l[0] == "h":
                        j = int(np.clip(np.searchsorted(self.L2, t2) - 1, 0, len(self.L2) - 2))
                        hl[l[1], j] += 1
                    else:
                        i = int(np.clip(np.searchsorted(self.L1, t1) - 1, 0, len(self.L1) - 2))
                        vl[i, l[1]] += 1
                exit_pts.append(pts[-1][:2] / sy.wr)
            # edges: entry edges are not landed on; compare interior lines and exit edges
            hmask = np.ones(len(self.L1), bool)
            hmask[-1] = False
            vmask = np.ones(len(self.L2), bool)
            vmask[0] = False
            bad_h = np.argwhere((hl != hc) & hmask[:, None])
            bad_v = np.argwhere((vl != vc) & vmask[None, :])
            if len(bad_h) or len(bad_v):
                problems.append(f"{len(bad_h) + len(bad_v)} grid segments where traced crossings != exact count")
            ex = np.array([p for p, _ in exits]).reshape(-1, 2)
            tr = np.array(exit_pts).reshape(-1, 2)
            if len(ex) != len(tr):
                problems.append(f"{len(tr)} traced exits, {len(ex)} exact exits")
            elif len(ex):
                scale = np.array([sy.q1, sy.q2])
                dmat = np.max(np.abs(ex[:, None, :] - tr[None, :, :]) / scale, axis=2)
                if np.max(np.min(dmat, axis=1)) > 1e-6 or np.max(np.min(dmat, axis=0)) > 1e-6:
                    problems.append("traced exits differ from the exact exits")
            if not problems:
                break
            self.stats["retraces"] += 1
            hmax, amax = hmax / 2, amax / 2
        self.stats["arcs"] = len(arcs)
        self.stats["certified"] = not problems
        for p in problems:
            self.warnings.append(p)
        return arcs

    # ------------------------------------------------------------ onset roots along the arcs
    def on_arc(self, s_val, xa, xb, zref):
        """the arc point with t2 - t1 = s_val (scaled), between arc points xa and xb."""
        sy = self.s
        sa, sb = xa[1] - xa[0], xb[1] - xb[0]
        f = (s_val - sa) / (sb - sa)
        cvec = np.zeros(sy.N + 2)
        cvec[0], cvec[1] = -1.0, 1.0
        x, _, ok = sy.correct(xa + f * (xb - xa), zref, cvec, s_val)
        if x[2:] @ zref < 0:
            x[2:] *= -1
        return x, ok

    def newton_full(self, x):
        """Newton on the full system R z = 0, a(z) = 0, zref.z = 1 in (wr t1, wr t2, z)."""
        sy, N, wr = self.s, self.s.N, self.s.wr
        x = x.copy()
        zref = x[2:].copy()
        J = np.zeros((N + 2, N + 2))
        prev = np.inf
        for it in range(40):
            R, R1, R2 = sy.Rhat(x[0] / wr, x[1] / wr, deriv=True)
            z = x[2:]
            F = np.r_[R @ z, sy.ellz @ z, zref @ z - 1.0]
            J[:N, 0], J[:N, 1], J[:N, 2:] = R1 @ z / wr, R2 @ z / wr, R
            J[N, :] = 0
            J[N, 2:] = sy.ellz
            J[N + 1, :] = 0
            J[N + 1, 2:] = zref
            dx = np.linalg.lstsq(J, -F, rcond=None)[0]
            step = np.linalg.norm(dx)
            if step > 0.5 * prev and prev < 1e-9 * (1 + np.linalg.norm(x[:2])):
                break                                # converged to rounding: no more progress
            x += dx
            prev = step
            if step < 1e-15 * (1 + np.linalg.norm(x[:2])):
                break
        x[2:] /= np.linalg.norm(x[2:])
        return x, prev < 1e-9 * (1 + np.linalg.norm(x[:2]))

    def roots(self, arcs):
        sy = self.s
        found = []
        for pts, _, tans in arcs:
            a = np.array([sy.onset(x) for x in pts])
            sv = pts[:, 1] - pts[:, 0]
            da = (tans[:, 2:] @ sy.ellz) / (tans[:, 1] - tans[:, 0])      # d a / d s from the tangents
            near = []                                  # intervals [k, k+1] that may hide two close roots
            for k in range(len(pts) - 1):
                if a[k] == 0.0:
                    found.append((pts[k], "exact"))
                elif a[k] * a[k + 1] < 0:
                    xa, xb = pts[k], pts[k + 1]
                    g = lambda sval: sy.onset(self.on_arc(sval, xa, xb, xa[2:])[0])
                    sr = _brent(g, sv[k], sv[k + 1])
                    found.append((self.on_arc(sr, xa, xb, xa[2:])[0], "simple"))
                elif a[k + 1] != 0.0:
                    # same sign at both ends: does the cubic Hermite interpolant of a dip through zero?
                    L = sv[k + 1] - sv[k]
                    u = np.linspace(0, 1, 33)
                    h00, h10 = 2 * u ** 3 - 3 * u ** 2 + 1, u ** 3 - 2 * u ** 2 + u
                    h01, h11 = -2 * u ** 3 + 3 * u ** 2, u ** 3 - u ** 2
                    c = h00 * a[k] + h10 * L * da[k] + h01 * a[k + 1] + h11 * L * da[k + 1]
                    if np.min(np.sign(a[k]) * c) < 0.05 * max(abs(a[k]), abs(a[k + 1])) or \
                            (k and abs(a[k]) < abs(a[k - 1]) and abs(a[k]) <= abs(a[k + 1]) and abs(a[k]) < 0.3):
                        near.append(k)
            for k in near:
                xa, xb = pts[k], pts[k + 1]
                lo_k = k - 1 if k else k                # include the previous interval (sampled local minimum)
                sgn = np.sign(a[k])

                def g(sval):
                    j = min(max(int(np.searchsorted(sv, sval) - 1), lo_k), k)
                    return sgn * sy.onset(self.on_arc(sval, pts[j], pts[j + 1], pts[j][2:])[0])
                r = minimize_scalar(g, bounds=(sv[lo_k], sv[k + 1]), method="bounded",
                                    options={"xatol": 1e-13 * max(1.0, abs(sv[k]))})
                smin = r.x
                gmin = g(smin)
                self.stats["dips_examined"] += 1
                if gmin < 0:
                    for lo, hi in ((sv[lo_k], smin), (smin, sv[k + 1])):
                        if g(lo) * g(hi) < 0:
                            sr = _brent(g, lo, hi)
                            j = min(max(int(np.searchsorted(sv, sr) - 1), lo_k), k)
                            found.append((self.on_arc(sr, pts[j], pts[j + 1], pts[j][2:])[0], "close pair"))
                elif gmin < 1e-6:
                    j = min(max(int(np.searchsorted(sv, smin) - 1), lo_k), k)
                    xm = self.on_arc(smin, pts[j], pts[j + 1], pts[j][2:])[0]
                    if gmin < 1e-13:                   # tangency: a double root (non-generic)
                        found.append((xm, "double"))
                    else:                              # reported, not a root
                        self.near_tangencies.append((xm[0] / sy.wr, xm[1] / sy.wr, float(gmin)))
        out = []
        for x, how in found:
            xn, ok = self.newton_full(x)
            if ok and np.linalg.norm((xn[:2] - x[:2])) < 1e-6 * (1 + np.linalg.norm(x[:2])):
                x = xn
            else:
                self.stats["newton_failures"] += 1
            t1, t2 = x[0] / sy.wr, x[1] / sy.wr
            if any(abs(t1 - o["t1"]) < 1e-9 * max(1, t1) and abs(t2 - o["t2"]) < 1e-9 * max(1, t2) for o in out):
                continue
            out.append({"t1": t1, "t2": t2, "how": how, "z": x[2:], "x": x})
        # is the sign change of the onset condition above its rounding noise? (it is not next to the t1 -> 0
        # axis, where a ~ t1^2 sinks into the rounding of the null vector)
        svals = np.array([o["x"][1] - o["x"][0] for o in out])
        for i, o in enumerate(out):
            x = o.pop("x")
            others = np.abs(np.delete(svals, i) - svals[i])
            delta = min(1e-4, 0.25 * others.min()) if len(others) else 1e-4
            sig = np.linalg.svd(sy.Rhat(x[0] / sy.wr, x[1] / sy.wr), compute_uv=False)
            noise = 1e-15 * sig[0] / max(sig[-2], 1e-300)
            v = sy.tangent(x)
            cvec = np.zeros(sy.N + 2)
            cvec[0], cvec[1] = -1.0, 1.0
            side = []
            for d in (-delta, delta):
                y, _, _ = sy.correct(x + d / (v[1] - v[0]) * v, x[2:], cvec, svals[i] + d)
                if y[2:] @ x[2:] < 0:
                    y[2:] *= -1
                side.append(sy.onset(y))
            o["onset_noise"], o["onset_at_pm_delta"] = float(noise), [float(a) for a in side]
            if o["how"] == "double":
                o["resolved"] = bool(min(abs(side[0]), abs(side[1])) > 10 * noise)
            else:
                o["resolved"] = bool(side[0] * side[1] < 0 and min(abs(side[0]), abs(side[1])) > 10 * noise)
        return out


# ---------------------------------------------------------------------------- verification
def _sym_fun(A, f):
    lam, Q = np.linalg.eigh((A + A.T) / 2)
    return (Q * f(lam)) @ Q.T


def verify(sy, t1, t2):
    """paper residuals (y = M^1/2 x, L1, L2 of section 3), physical propagation, admissibility."""
    n, M, K, w, g0 = sy.n, sy.M, sy.K, sy.w, sy.g0
    Mhi = _sym_fun(M, lambda l: 1 / np.sqrt(l))
    K1 = Mhi @ K @ Mhi
    K1 = (K1 + K1.T) / 2
    w1 = Mhi @ w
    J1 = np.eye(n) - np.outer(w1, w1) / (w1 @ w1)
    K1h, K1hi = _sym_fun(K1, np.sqrt), _sym_fun(K1, lambda l: 1 / np.sqrt(l))
    # L1 = K1^1/2 ; L2 = K1^-1/2 (K1^1/2 J1 K1^1/2)^1/2 K1^1/2  (a square root of J1 K1, eq. 3.8)
    l1, Q1 = np.linalg.eigh(K1)
    l1 = np.sqrt(l1)
    Sm = K1h @ J1 @ K1h
    l2, Q2 = np.linalg.eigh((Sm + Sm.T) / 2)
    l2 = np.sqrt(np.clip(l2, 0, None))
    P2, P2i = K1hi @ Q2, Q2.T @ K1h
    L2 = (P2 * l2) @ P2i
    L2sq_err = np.linalg.norm(L2 @ L2 - J1 @ K1) / np.linalg.norm(K1)

    def f1(f):
        return (Q1 * f(l1)) @ Q1.T

    def f2(f):
        return (P2 * f(l2)) @ P2i
    R2 = np.block([[f1(lambda l: l * np.sin(t1 * l)), f1(lambda l: np.cos(t1 * l))],
                   [-f2(lambda l: l * np.sin(t2 * l)), f2(lambda l: np.cos(t2 * l))]])
    sv = np.linalg.svd(R2, compute_uv=False)
    det_rel = abs(np.linalg.det(R2)) / np.prod(np.linalg.norm(R2, axis=1))
    y = np.linalg.svd(R2)[2][-1]
    y0, yd0 = y[:n], y[n:]
    ons = w @ np.linalg.solve(M, K) @ Mhi           # w^T M^-1 K M^-1/2
    onset_rel = abs(ons @ y0) / (np.linalg.norm(ons) * np.linalg.norm(y0))
    p = w @ Mhi @ y0
    p0_rel = abs(p) / (np.linalg.norm(w @ Mhi) * np.linalg.norm(y0))
    fac = -g0 / p                                    # eq. (5.2)
    x0, v0 = fac * (Mhi @ y0), fac * (Mhi @ yd0)
    # physical propagation: contact 2 t2 then flight 2 t1, scipy expm of the first-order systems
    I, Z = np.eye(n), np.zeros((n, n))
    A1 = np.block([[Z, I], [-np.linalg.solve(M, K), Z]])
    A2 = np.block([[Z, I], [-np.linalg.solve(M, sy.Kt), Z]])
    X0 = np.r_[x0, v0]
    Xc = sla.expm(2 * t2 * A2) @ X0
    Xmid = sla.expm(t2 * A2) @ X0
    Xf = sla.expm(2 * t1 * A1) @ Xc
    def energy(X):                                    # (B^1/2 x, v): |.|^2 = 2 x energy in the M-norm
        return np.r_[sy.Bh @ X[:n], X[n:]]
    return_error = np.linalg.norm(energy(Xf - X0)) / np.linalg.norm(energy(X0))
    scale_x = np.linalg.norm(x0) + 1e-300
    contact_gap_drift = max(abs(w @ Xc[:n] + g0), abs(w @ Xmid[:n] + g0)) / (abs(g0) + scale_x)
    onset_vel = abs(w @ v0) / np.linalg.norm(energy(X0))
    # admissibility (ineqs. 5.3), sampled on the physical modes, then refined around the sampled minima
    q0 = sy.V1i @ x0
    qd0 = sy.V1i @ v0
    c = w @ np.linalg.solve(M, w)

    def gap(t):  # flight on [-2 t1, 0], time measured from onset (negative)
        t = np.atleast_1d(t)
        q = np.cos(np.outer(t, sy.om)) * q0 + np.sin(np.outer(t, sy.om)) / sy.om * qd0
        return q @ (sy.V1.T @ w) + g0
    a0 = sy.V2i @ x0
    ad0 = sy.V2i @ v0
    dd = sy.d

    def force(t):  # contact on [0, 2 t2]: lambda = w^T M^-1 K x / (w^T M^-1 w)   (eq. 2.7)
        t = np.atleast_1d(t)
        th = np.outer(t, dd)
        sinc_t = np.where(dd > 0, np.sin(th) / np.where(dd > 0, dd, 1), t[:, None])
        q = np.cos(th) * a0 + sinc_t * ad0
        return (q @ (sy.V2.T @ sy.ell)) / c

    def minimum(fun, a, b, freq):
        ns = int(min(400000, max(4000, 40 * (b - a) * freq / (2 * PI) * 10)))
        ts = np.linspace(a, b, ns)
        vals = fun(ts)
        k = int(np.argmin(vals))
        lo, hi = ts[max(k - 1, 0)], ts[min(k + 1, ns - 1)]
        if hi > lo:
            r = minimize_scalar(lambda t: float(fun(t)[0]), bounds=(lo, hi), method="bounded",
                                options={"xatol": 1e-14 * max(1, abs(hi))})
            return min(vals[k], r.fun), vals
        return vals[k], vals
    gmin, gv = minimum(gap, -2 * t1, 0.0, sy.om.max())
    fmin, fv = minimum(force, 0.0, 2 * t2, max(sy.d.max(), 1e-300))
    fscale = max(np.max(np.abs(fv)), 1e-300)
    gscale = abs(g0)
    admissible = bool(gmin >= -1e-9 * gscale and fmin >= -1e-9 * fscale)
    return {
        "det_R2_rel": float(det_rel), "sigma_min_over_max_R2": float(sv[-1] / sv[0]),
        "onset_rel": float(onset_rel), "p0_rel": float(p0_rel), "L2_sq_err": float(L2sq_err),
        "return_error": float(return_error), "contact_gap_drift": float(contact_gap_drift),
        "onset_velocity_rel": float(onset_vel),
        "min_gap": float(gmin), "min_force": float(fmin), "min_gap_rel": float(gmin / gscale),
        "min_force_rel": float(fmin / fscale), "admissible": admissible,
        "x0": x0.tolist(), "v0": v0.tolist(),
    }


def default_lower(sy):
    return 1e-4 * sy.q1, 1e-4 * sy.q2


def solve(system, t1min, t1max, t2min, t2max, grid=2, verify_roots=True):
    """all SPPs (t1, t2) in (t1min, t1max] x (t2min, t2max]; lower ends <= 0 mean the default 1e-4 pi/(2 f_max)."""
    t0 = time.time()
    sy = SPPSystem(system["M"], system["K"], system["w"], system["g0"])
    d1, d2 = default_lower(sy)
    t1min = d1 if t1min <= 0 else t1min
    t2min = d2 if t2min <= 0 else t2min
    fd = Finder(sy, t1min, t1max, t2min, t2max, grid=grid)
    arcs = fd.trace_all()
    raw = fd.roots(arcs)
    roots, rejected = [], []
    for r in sorted(raw, key=lambda r: (r["t1"] + r["t2"], r["t1"])):
        if not (t1min < r["t1"] <= t1max and t2min < r["t2"] <= t2max):
            continue
        x0n = sy.Bhi @ r["z"][:sy.n]
        p0 = abs(sy.w @ x0n) / (np.linalg.norm(x0n) + 1e-300)
        rec = {"t1": r["t1"], "t2": r["t2"], "period": 2 * (r["t1"] + r["t2"]), "found_as": r["how"]}
        if p0 < 1e-10:
            rec["reason"] = "p0 = w^T x0 = 0: gap closure impossible"
            rejected.append(rec)
            continue
        if not r["resolved"]:
            rec["reason"] = (f"sign change of the onset condition at rounding level (|a| = "
                             f"{max(map(abs, r['onset_at_pm_delta'])):.1e} at +-1e-4 along the curve, "
                             f"noise {r['onset_noise']:.1e}): the t1 -> 0 or t2 -> 0 limit, not resolved")
            rejected.append(rec)
            continue
        if verify_roots:
            rec.update(verify(sy, r["t1"], r["t2"]))
            ok = rec["det_R2_rel"] < 1e-8 and rec["sigma_min_over_max_R2"] < 1e-10 and rec["onset_rel"] < 1e-8 \
                and rec["return_error"] < 1e-8 and rec["contact_gap_drift"] < 1e-8 and rec["onset_velocity_rel"] < 1e-8
            rec["verified"] = bool(ok)
            if not ok:
                fd.warnings.append(f"root ({r['t1']:.10g}, {r['t2']:.10g}) fails verification")
        roots.append(rec)
    fd.stats["seconds"] = time.time() - t0
    fd.stats["near_tangencies"] = [t for t in fd.near_tangencies   # (the t1 -> 0, t2 -> 0 limits excluded)
                                   if 2 * t1min < t[0] <= t1max and 2 * t2min < t[1] <= t2max]
    return {"window": [t1min, t1max, t2min, t2max], "roots": roots, "rejected": rejected,
            "warnings": fd.warnings, "stats": fd.stats,
            "frequencies": {"flight": sy.om.tolist(), "contact": sy.d.tolist()}}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("system")
    ap.add_argument("--window", nargs=4, type=float, required=True, metavar=("T1MIN", "T1MAX", "T2MIN", "T2MAX"))
    ap.add_argument("--grid", type=int, default=2, help="certification grid lines per quarter period (default 2)")
    ap.add_argument("--json")
    ap.add_argument("--quiet", action="store_true")
    a = ap.parse_args(argv)
    with open(a.system) as f:
        system = json.load(f)
    res = solve(system, *a.window, grid=a.grid)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)
    if not a.quiet:
        print(f"{'#':>3} {'t1':>18} {'t2':>18} {'adm':>4} {'detR2':>8} {'onset':>8} {'return':>8} "
              f"{'min_gap':>9} {'min_force':>9}")
        for i, r in enumerate(res["roots"]):
            print(f"{i:3d} {r['t1']:18.12g} {r['t2']:18.12g} {'yes' if r['admissible'] else 'no':>4} "
                  f"{r['det_R2_rel']:8.1e} {r['onset_rel']:8.1e} {r['return_error']:8.1e} "
                  f"{r['min_gap_rel']:9.1e} {r['min_force_rel']:9.1e}")
    for r in res["rejected"]:
        print(f"rejected ({r['t1']:.12g}, {r['t2']:.12g}): {r['reason']}")
    for wmsg in res["warnings"]:
        print("warning:", wmsg, file=sys.stderr)
    st = res["stats"]
    w = res["window"]
    print(f"brute_force: {len(res['roots'])} roots ({sum(r['admissible'] for r in res['roots'])} admissible) in "
          f"({w[0]:.6g}, {w[1]:.6g}] x ({w[2]:.6g}, {w[3]:.6g}]; {st['arcs']} arcs, {st['steps']} steps, "
          f"grid {st['grid'][0]}x{st['grid'][1]}, certified={st['certified']}, {st['seconds']:.2f} s")
    return 0 if st["certified"] else 2


if __name__ == "__main__":
    sys.exit(main())
