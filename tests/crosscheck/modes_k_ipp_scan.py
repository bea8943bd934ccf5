#!/usr/bin/env python3
"""Admissible genuine k-IPPs (k = 2, 3, ...) of a system at sampled energies, found without spp and without any
symmetry assumption, against `spp modes` (issue 15: the yardstick for k >= 2).

Independent of spp: numpy's own eigensolve gives the modal form (omega, b = Phi^T w, the modes that see the
obstacle); the flight is the exact modal flow q(t) = cos(W t) q + W^-1 sin(W t) q', the impact (e = 1) reflects the
modal velocity in b^perp. Unknowns: the state (q, q') just after an impact and the k flight durations; equations:
that state on the obstacle, the gap 0 after each flight, the state back after the k-th impact, the energy = E (one
more equation than unknowns, consistent: energy is conserved). Solved by least squares (scipy, Levenberg-Marquardt)
from many random starts at each sampled energy. A solution is kept when its residual is below 1e-10, every flight is
longer than 1e-6 T, it is no repetition of an orbit with fewer impacts (no cyclic shift of its impact sequence maps
it onto itself), its period is <= T_max, and it is admissible: every impact arrives towards the obstacle, the gap is
> 0 inside every flight (sampled at 400 points per flight, each local minimum refined by a bounded scalar
minimisation). Orbits are deduplicated by (E, T, flight durations up to cyclic shift).

An orbit is listed by spp when a k family of `spp modes` (admissible points, multiplicity 1) has a segment that
passes its energy within 1e-3 relative in period, with the flight durations (interpolated, up to cyclic shift and
time reversal: a non-reversible family stands for its time reverse too) within 1e-2 T.

  modes_k_ipp_scan.py SYSTEM.json --k 2 3 --energies E1 E2 ... --period-max T [--starts N] [--seed S]
                      [--spp build/spp --spp-args "--multiples 6 --through-inadmissible"] [--modes MODES.json]
prints each orbit found (k, E, T, flights, impact speeds, listed or not) and "k K: listed L of N orbits".
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.linalg
import scipy.optimize


class Modal:
    def __init__(self, path):
        with open(path) as f:
            s = json.load(f)
        M, K, w = (np.array(s[key], dtype=float) for key in ("M", "K", "w"))
        self.g0 = float(s["g0"])
        lam, Phi = scipy.linalg.eigh(K, M)
        b = Phi.T @ w
        keep = np.abs(b) > 1e-10 * np.linalg.norm(b)
        self.omega, self.b = np.sqrt(lam[keep]), b[keep]
        self.n = len(self.b)
        self.bh = self.b / np.linalg.norm(self.b)

    def flow(self, q, p, t):
        c, s = np.cos(self.omega * t), np.sin(self.omega * t)
        return c * q + s / self.omega * p, -self.omega * s * q + c * p

    def reflect(self, p):
        return p - 2.0 * (self.bh @ p) * self.bh

    def energy(self, q, p):
        return 0.5 * (p @ p + (self.omega**2 * q**2).sum())

    def residual(self, y, k, energy):
        n = self.n
        q, p, taus = y[:n], y[n : 2 * n], y[2 * n :]
        r = [(self.b @ q + self.g0) / self.g0]
        qq, pp = q, p
        for j in range(k):
            qq, pp = self.flow(qq, pp, taus[j])
            if j < k - 1:
                r.append((self.b @ qq + self.g0) / self.g0)
            pp = self.reflect(pp)
        scale = np.sqrt(2 * energy)
        r.extend((self.omega * (qq - q)) / scale)
        r.extend((pp - p) / scale)
        r.append(self.energy(q, p) / energy - 1.0)
        return np.array(r)

    def impacts(self, y, k):
        """(pre-impact speeds towards the obstacle, min gap over the open flights) along one period."""
        n = self.n
        q, p, taus = y[:n], y[n : 2 * n], y[2 * n :]
        speeds, min_gap = [], np.inf
        for j in range(k):
            min_gap = min(min_gap, self.flight_min_gap(q, p, taus[j]))
            q, p = self.flow(q, p, taus[j])
            speeds.append(-(self.b @ p))
            p = self.reflect(p)
        return np.array(speeds), min_gap

    def gap(self, q, p, t):
        t = np.atleast_1d(t)[:, None]
        return self.g0 + (self.b * (np.cos(self.omega * t) * q + np.sin(self.omega * t) / self.omega * p)).sum(axis=1)

    def flight_min_gap(self, q, p, tau, samples=400):
        t = np.linspace(0.0, tau, samples + 1)[1:-1]
        g = self.gap(q, p, t)
        best = g.min()
        h = t[1] - t[0]
        interior = np.nonzero((g[1:-1] <= g[:-2]) & (g[1:-1] <= g[2:]))[0] + 1
        for i in list(interior) + [0, len(t) - 1]:
            lo, hi = max(t[i] - h, 1e-12 * tau), min(t[i] + h, tau * (1 - 1e-12))
            res = scipy.optimize.minimize_scalar(
                lambda s: self.gap(q, p, s)[0], bounds=(lo, hi), method="bounded", options={"xatol": 1e-13 * tau}
            )
            # a minimum at a flight's end is the impact itself (gap 0): only interior minima count
            if lo + 1e-9 * tau < res.x < hi - 1e-9 * tau or (0 < i < len(t) - 1):
                if 1e-7 * tau < res.x < tau * (1 - 1e-7):
                    best = min(best, res.fun)
        return best


def least_period_shift(sysm, y, k):
    """The smallest shift d < k of the impact sequence that maps the orbit onto itself (k: none)."""
    n = sysm.n
    q, p, taus = y[:n].copy(), y[n : 2 * n].copy(), y[2 * n :]
    states = []
    for j in range(k):
        states.append(np.concatenate([sysm.omega * q, p]))
        q, p = sysm.flow(q, p, taus[j])
        p = sysm.reflect(p)
    scale = np.sqrt(2 * sysm.energy(y[:n], y[n : 2 * n]))
    for d in range(1, k):
        if k % d == 0 and all(np.linalg.norm(states[i] - states[(i + d) % k]) <= 1e-6 * scale for i in range(k)):
            return d
    return k


def canonical(taus):
    """The cyclic rotation of the flight durations that is lexicographically smallest (rounded for the comparison)."""
    k = len(taus)
    rots = [tuple(np.roll(taus, -i)) for i in range(k)]
    return min(rots, key=lambda r: tuple(np.round(r, 6)))


def search(sysm, k, energy, period_max, starts, rng):
    n, g0, b = sysm.n, sysm.g0, sysm.b
    found = []
    for _ in range(starts):
        # a random state on the obstacle with energy `energy` and an outgoing velocity; random flight durations
        c = rng.normal(size=n)
        c -= (sysm.bh @ c) * sysm.bh
        q = -g0 * b / (b @ b) + c * rng.uniform(0, 1) * np.sqrt(2 * energy) / sysm.omega.max()
        pot = 0.5 * (sysm.omega**2 * q**2).sum()
        if pot >= energy:
            continue
        p = rng.normal(size=n)
        p *= np.sqrt(2 * (energy - pot)) / np.linalg.norm(p)
        if sysm.bh @ p < 0:
            p = sysm.reflect(p)
        taus = rng.dirichlet(np.ones(k)) * rng.uniform(0.05, 1.0) * period_max
        y0 = np.concatenate([q, p, taus])
        try:
            sol = scipy.optimize.least_squares(sysm.residual, y0, args=(k, energy), method="lm", xtol=1e-15,
                                               ftol=1e-15, gtol=1e-15, max_nfev=200 * len(y0))
        except (ValueError, FloatingPointError):
            continue
        y = sol.x
        if not np.all(np.isfinite(y)) or np.linalg.norm(sysm.residual(y, k, energy)) > 1e-10:
            continue
        taus = y[2 * n :]
        T = taus.sum()
        if np.any(taus <= 1e-6 * max(T, 1e-300)) or T > period_max:
            continue
        if least_period_shift(sysm, y, k) < k:
            continue  # a repetition of an orbit with fewer impacts
        speeds, min_gap = sysm.impacts(y, k)
        if speeds.min() <= 1e-7 * g0 * sysm.omega.max() or min_gap <= 1e-9 * g0:
            continue  # not admissible (or grazing)
        key = canonical(taus)
        if any(abs(o["T"] - T) <= 1e-7 * T and np.allclose(o["canonical"], key, atol=1e-6 * T) for o in found):
            continue
        found.append({"k": k, "E": energy, "T": T, "taus": list(taus), "canonical": list(key),
                      "speeds": list(speeds), "min_gap": min_gap, "x": list(y)})
    return found


def pattern_distance(a, b):
    """Smallest max difference between flight sequences a and b over cyclic shifts and time reversal of b."""
    a, b = np.asarray(a), np.asarray(b)
    best = np.inf
    for seq in (b, b[::-1]):
        for i in range(len(seq)):
            best = min(best, np.abs(a - np.roll(seq, i)).max())
    return best


def listed(orbit, families):
    E, T, k = orbit["E"], orbit["T"], orbit["k"]
    for f in families:
        if f["k"] != k:
            continue
        pts = f["points"]
        for a, c in zip(pts, pts[1:]):
            if not (a["admissible"] and c["admissible"]) or a.get("multiplicity", 1) != 1:
                continue
            ea, ec = a["energy"], c["energy"]
            if (ea - E) * (ec - E) > 0:
                continue
            s = 0.5 if ec == ea else (E - ea) / (ec - ea)
            Ts = a["period"] + s * (c["period"] - a["period"])
            fa = np.diff(list(a["impact_times"]) + [a["period"]])
            fc = np.diff(list(c["impact_times"]) + [c["period"]])
            if abs(Ts - T) <= 1e-3 * T and pattern_distance(orbit["taus"], fa + s * (fc - fa)) <= 1e-2 * T:
                return f["label"]
    return None


def main(argv=None):
    """Runs the scan (and the comparison); returns {k: (listed, found)} (listed None without --spp / --modes)."""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("system")
    ap.add_argument("--k", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--energies", type=float, nargs="+", required=True)
    ap.add_argument("--period-max", type=float, required=True)
    ap.add_argument("--starts", type=int, default=2000, help="random starts per k and energy")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--spp", help="spp CLI: run `spp modes` and compare")
    ap.add_argument("--spp-args", default="", help="extra `spp modes` options (one string)")
    ap.add_argument("--modes", help="a `spp modes --json` file to compare with (instead of --spp)")
    ap.add_argument("--json", help="write the orbits found (and whether listed) here")
    args = ap.parse_args(argv)

    sysm = Modal(args.system)
    rng = np.random.default_rng(args.seed)
    families = None
    if args.spp:
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "modes.json")
            kk = f"{min(args.k)}..{max(args.k)}" if len(args.k) > 1 else str(args.k[0])
            cmd = [args.spp, "modes", args.system, "--k", kk, "--energy-max", str(max(args.energies) * 1.05),
                   "--json", out] + args.spp_args.split()
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            with open(out) as f:
                families = json.load(f)["families"]
    elif args.modes:
        with open(args.modes) as f:
            families = json.load(f)["families"]

    orbits = []
    for k in args.k:
        for E in args.energies:
            orbits.extend(search(sysm, k, E, args.period_max, args.starts, rng))
    summary = {}
    for o in sorted(orbits, key=lambda o: (o["k"], o["E"], o["T"])):
        o["listed"] = listed(o, families) if families is not None else None
        flights = " ".join(f"{t:.6f}" for t in o["canonical"])
        speeds = " ".join(f"{v:.3f}" for v in o["speeds"])
        mark = "" if families is None else (f"listed ({o['listed']})" if o["listed"] else "NOT LISTED")
        print(f"k {o['k']} E {o['E']:.6g} T {o['T']:.6f} flights {flights} speeds {speeds} {mark}")
        s = summary.setdefault(o["k"], [0, 0])
        s[0] += o["listed"] is not None
        s[1] += 1
    counts = {}
    for k in args.k:
        s = summary.get(k, [0, 0])
        counts[k] = (s[0] if families is not None else None, s[1])
        if families is not None:
            print(f"k {k}: listed {s[0]} of {s[1]} orbits")
        else:
            print(f"k {k}: {s[1]} orbits")
    if args.json:
        with open(args.json, "w") as f:
            json.dump([{key: v for key, v in o.items()} for o in orbits], f)
    return counts


if __name__ == "__main__":
    main()
