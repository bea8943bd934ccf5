#!/usr/bin/env python3
"""Why a certified solve ends incomplete next to t2 = c - t1: nearly coincident zero curves of H (issue 12).

For a dense system file (M, K, w as lists of rows), forms the modal form's H(t1, t2) = W tan(W t1) + G D tan(D t2) G^T
(docs: modal form §1-2, in numpy, independently of spp), and for each t1 of a grid finds the zero curves lambda_k = 0
next to t2 = c - t1 (brentq on the k-th eigenvalue): the curve's offset t2 - (c - t1), the onset function
g = z^T b / |z| on it, and the neighbouring eigenvalues lambda_{k-1}, lambda_{k+1} there (the gaps the step
certificate divides by). Also prints d_j / (j d_1): the contact frequencies' distance from integer multiples, which puts
an image of the origin at t2 = pi / d_1 (tan(d_j t2) = 0 for every j at once). "turn": the angle (rad) between b and
curve k's b at the previous t1 of the list (none across a pole line; how fast the null vector turns along the curve).

usage: cluster_near_zero.py SYSTEM.json [--c 1.0] [--t1 0.01,0.05,0.1 | --t1 FIRST:LAST:COUNT] [--width 0.004]
"""
import argparse
import json

import numpy as np
import scipy.linalg as sl
from scipy.optimize import brentq


def modal_h(system):
    M, K, w = (np.array(system[k], dtype=float) for k in ("M", "K", "w"))
    om2, phi = sl.eigh(K, M)
    om = np.sqrt(om2)
    u = phi.T @ w
    u /= np.linalg.norm(u)
    z = om * u
    e, V = np.linalg.eigh(np.diag(om2) - np.outer(z, z))
    keep = np.argsort(e)[1:]  # drop the constrained direction (eigenvalue 0)
    d, G = np.sqrt(e[keep]), V[:, keep]
    return om, d, G, z / np.linalg.norm(z)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("system")
    ap.add_argument("--c", type=float, default=1.0, help="curves next to t2 = c - t1")
    ap.add_argument("--t1", default="0.006,0.01,0.02,0.05,0.1")
    ap.add_argument("--width", type=float, default=0.004, help="half-width of the t2 bracket around c - t1")
    a = ap.parse_args()
    with open(a.system) as f:
        om, d, G, zh = modal_h(json.load(f))
    print("omega", om)
    print("d", d, "d_j / (j d_1) - 1:", d / (d[0] * np.arange(1, len(d) + 1)) - 1)

    def H(t1, t2):
        return np.diag(om * np.tan(om * t1)) + G @ np.diag(d * np.tan(d * t2)) @ G.T

    if ":" in a.t1:
        first, last, count = a.t1.split(":")
        grid = np.linspace(float(first), float(last), int(count))
    else:
        grid = [float(x) for x in a.t1.split(",")]
    print("t1, k, offset t2 - (c - t1), g, lambda_{k-1}, lambda_{k+1}, turn")
    previous, last_t1 = {}, None
    for t1 in grid:
        # across a pole line the curves' indices k shift: no turn is compared over one
        def cell(x):
            return np.concatenate([np.floor(om * x / np.pi + 0.5), np.floor(d * (a.c - x) / np.pi + 0.5)])

        if last_t1 is not None and np.any(cell(last_t1) != cell(t1)):
            previous = {}
        last_t1 = t1
        for k in range(len(om)):
            f = lambda t2: np.linalg.eigvalsh(H(t1, t2))[k]  # noqa: E731
            lo, hi = a.c - t1 - a.width, a.c - t1 + a.width
            if f(lo) * f(hi) > 0:
                previous.pop(k, None)
                continue
            t2 = brentq(f, lo, hi, xtol=1e-16)
            lam, V = np.linalg.eigh(H(t1, t2))
            b = V[:, k] * np.sign(V[np.argmax(np.abs(V[:, k])), k])
            below = lam[k - 1] if k > 0 else -np.inf
            above = lam[k + 1] if k + 1 < len(lam) else np.inf
            if k in previous and b @ previous[k] < 0:  # oriented continuously along the curve (g's sign then tells)
                b = -b
            turn = np.arccos(min(1.0, abs(b @ previous[k]))) if k in previous else float("nan")
            previous[k] = b
            print(f"{t1:.4g} {k} {t2 - (a.c - t1):+.3e} {zh @ b:+.3e} {below:+.3e} {above:+.3e} {turn:.1e}")


if __name__ == "__main__":
    main()
