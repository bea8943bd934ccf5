#!/usr/bin/env python3
"""Every symmetric 1-IPP of a system, by a scan of its explicit form, against `spp modes --k 1` (issue 15, D1).

Independent of spp's continuation: docs/modes.md §2 gives the (flight, impact) 1-IPP of half period tau in closed
form, q_A = c (W sin(W tau))^-1 b, c = -g0 / sum_i b_i^2 cot(omega_i tau) / omega_i (numpy's own eigensolve, no spp
code). This scans tau over (0, T_max / 2] on a fine grid, marks each orbit admissible (incoming impact speed > 0, gap
> 0 sampled over the open flight) with energy <= E_max, and cuts the admissible tau into branches (maximal runs).
A branch is listed by spp when an admissible point of a k = 1 family of `spp modes` has its half period inside the
branch, with the branch's energy there (to 1e-6 relative).

  modes_one_ipp_scan.py SYSTEM.json --energy-max E --period-max T [--spp build/spp] [--multiples J]
                        [--through-inadmissible]
prints each branch (T range, E range, listed or not) and "listed L of B branches".
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
import scipy.linalg


def modal(path):
    with open(path) as f:
        s = json.load(f)
    M, K, w, g0 = (np.array(s[key], dtype=float) for key in ("M", "K", "w", "g0"))
    lam, Phi = scipy.linalg.eigh(K, M)  # M-normalised
    omega = np.sqrt(lam)
    b = Phi.T @ w
    keep = np.abs(b) > 1e-10 * np.linalg.norm(b)  # modes that never see the obstacle carry no 1-IPP of their own
    return omega[keep], b[keep], float(g0)


def scan(omega, b, g0, energy_max, period_max, points=200_000, flight_samples=300):
    """tau grid, energy and admissibility of the explicit 1-IPP at each tau."""
    tau = np.linspace(period_max / 2 / points, period_max / 2, points)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        s = np.sin(np.outer(tau, omega))
        c = np.cos(np.outer(tau, omega))
        S = (b**2 * c / s / omega).sum(axis=1)
        coef = -g0 / S
        q = coef[:, None] * b / (omega * s)  # q_A: a turning point, velocity 0
        energy = 0.5 * (omega**2 * q**2).sum(axis=1)
        # incoming normal speed at B (tau): -b^T q'(tau), q'(tau) = -W sin(W tau) q_A
        speed = (b * omega * s * q).sum(axis=1)
        ok = np.isfinite(energy) & (energy <= energy_max) & (speed > 0)
        gap_min = np.full(points, np.inf)
        idx = np.nonzero(ok)[0]
        frac = np.linspace(0.0, 1.0, flight_samples, endpoint=False)  # t / tau in [0, 1): the open flight and A
        for chunk in np.array_split(idx, max(1, len(idx) // 2000)):
            t = tau[chunk, None] * frac  # (c, F)
            g = g0 + np.einsum("ci,cfi->cf", b * q[chunk], np.cos(t[:, :, None] * omega))
            gap_min[chunk] = np.minimum(g.min(axis=1), refined_minima(g, tau[chunk], frac, b * q[chunk], omega, g0))
        ok &= gap_min > 0
    return tau, energy, ok


def refined_minima(g, tau, frac, bq, omega, g0, keep=4, fine=64):
    """The gap's smallest value near the `keep` lowest sampled local minima of each row, on a grid `fine` times
    finer: a dip narrower than the coarse spacing (a tangency at period multiples turning into a crossing) is
    missed by the coarse samples alone (a random 4-dof system: gap -1e-3 between samples, listed as admissible)."""
    inner = (g[:, 1:-1] <= g[:, :-2]) & (g[:, 1:-1] <= g[:, 2:])
    masked = np.where(inner, g[:, 1:-1], np.inf)
    k = min(keep, masked.shape[1])
    idx = np.argpartition(masked, k - 1, axis=1)[:, :k] + 1  # columns of g
    dt = (frac[1] - frac[0]) * tau  # coarse spacing per row
    offs = np.linspace(-1.0, 1.0, fine)
    t = (frac[idx] * tau[:, None])[:, :, None] + offs * dt[:, None, None]  # (c, k, fine)
    gf = g0 + np.einsum("ci,ckfi->ckf", bq, np.cos(t[..., None] * omega))
    return gf.reshape(len(tau), -1).min(axis=1)


def branches(tau, energy, ok):
    out, start = [], None
    for i, a in enumerate(np.append(ok, False)):
        if a and start is None:
            start = i
        elif not a and start is not None:
            if i - start >= 3:  # a run of 1-2 grid points is a grid artefact at a grazing end
                out.append((start, i - 1))
            start = None
    return out


def spp_points(spp, system, energy_max, multiples, through_inadmissible=False):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "m.json")
        cmd = [spp, "modes", system, "--k", "1", "--energy-max", str(energy_max), "--json", out] + os.environ.get("SPP_MODES_ARGS", "").split()
        if multiples:
            cmd += ["--multiples", str(multiples)]
        if through_inadmissible:
            cmd += ["--through-inadmissible"]
        subprocess.run(cmd, check=True, capture_output=True)
        with open(out) as f:
            r = json.load(f)
    return [(p["period"], p["energy"]) for fam in r["families"] if fam["k"] == 1 for p in fam["points"]
            if p["admissible"]]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("system")
    ap.add_argument("--energy-max", type=float, required=True)
    ap.add_argument("--period-max", type=float, required=True)
    ap.add_argument("--spp", default=os.environ.get("SPP_CLI", "build/spp"))
    ap.add_argument("--multiples", type=int, default=0)
    ap.add_argument("--through-inadmissible", action="store_true", help="pass --through-inadmissible to spp modes")
    a = ap.parse_args(argv)
    omega, b, g0 = modal(a.system)
    tau, energy, ok = scan(omega, b, g0, a.energy_max, a.period_max)
    found = branches(tau, energy, ok)
    pts = spp_points(a.spp, a.system, a.energy_max, a.multiples, a.through_inadmissible)
    listed = 0
    for i0, i1 in found:
        lo, hi = tau[i0], tau[i1]
        hit = False
        for T, E in pts:
            if lo <= T / 2 <= hi:
                e_bf = np.interp(T / 2, tau[i0:i1 + 1], energy[i0:i1 + 1])
                hit = hit or abs(e_bf - E) <= 1e-3 * E  # the grid's interpolation error, not spp's
        listed += hit
        print(f"T [{2 * lo:.4f}, {2 * hi:.4f}]  E [{energy[i0:i1 + 1].min():.4g}, {energy[i0:i1 + 1].max():.4g}]  "
              f"{'listed' if hit else 'MISSED'}")
    print(f"listed {listed} of {len(found)} branches")
    return listed, len(found)


if __name__ == "__main__":
    main()
    sys.exit(0)
