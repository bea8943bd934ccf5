"""Finite-difference monodromy of the exact simulator against spp's Floquet monodromy (docs/stability.md).

For each admissible SPP chosen below and each impact law e, the one-period map of the event-driven simulator from
the mid-flight state is differentiated by one-sided differences of relative step delta; the relative error
|J - Mono_mid| / |Mono_mid| (Frobenius) must fall like delta^(1/3) (x 2.15 per decade). Then long simulations from
a perturbed mid-flight state: the distance to the orbit on the release section (state at each release), after 1, 10,
100, 1000 periods, and the period at which it first exceeds 1e-3.

    PYTHONPATH=build/python /usr/bin/python3 tests/crosscheck/floquet_convergence.py [--long [--eps E] [--energy S]]
"""
import argparse

import numpy as np
import scipy.linalg as sl

import spp


def flight_flow(s, t):
    n = s.n
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -np.linalg.solve(s.M, s.K)
    return sl.expm(t * A)


def mid_flight(s, sol):
    """State at mid-flight (t = -t1) and the predicted monodromy from there."""
    mono, x0, v0, _ = spp.monodromy(s, sol.t1, sol.t2)
    X0 = np.concatenate([x0, v0])
    return flight_flow(s, -sol.t1) @ X0, flight_flow(s, -sol.t1) @ mono @ flight_flow(s, sol.t1)


def one_period(s, X, T, e):
    n = s.n
    r = spp.simulate(s, X[:n], X[n:], duration=T, restitution=e, sample_times=[T], sample_events=False)
    assert r.status == "success", r.status
    return np.concatenate([r.x[-1], r.v[-1]])


def fd_monodromy(s, Xm, T, e, delta):
    base = one_period(s, Xm, T, e)
    h = delta * np.linalg.norm(Xm)
    J = np.empty((Xm.size, Xm.size))
    for i in range(Xm.size):
        X = Xm.copy()
        X[i] += h
        J[:, i] = (one_period(s, X, T, e) - base) / h
    return J


def nontrivial_radius(J):
    """Largest |eigenvalue| once the two closest to 1 (flow direction, energy) are removed."""
    ev = np.linalg.eigvals(J)
    keep = np.argsort(np.abs(ev - 1.0))[2:]
    return np.max(np.abs(ev[keep])) if keep.size else 0.0


def convergence(cases, deltas, laws):
    print("| system | SPP (t1, t2) | rho | e | " + " | ".join(f"delta = {d:.0e}" for d in deltas) + " | rate |")
    print("|---|---|---|---|" + "---|" * len(deltas) + "---|")
    for name, s, sol in cases:
        Xm, mono_mid = mid_flight(s, sol)
        for e in laws:
            errs, rhos = [], []
            for d in deltas:
                J = fd_monodromy(s, Xm, sol.period, e, d)
                errs.append(np.linalg.norm(J - mono_mid) / np.linalg.norm(mono_mid))
                rhos.append(nontrivial_radius(J))
            rate = np.polyfit(np.log10(deltas), np.log10(errs), 1)[0]
            cells = " | ".join(f"{a:.2e} ({r:.4f})" for a, r in zip(errs, rhos))
            print(f"| {name} | ({sol.t1:.5f}, {sol.t2:.5f}) | {sol.spectral_radius:.6f} | {e} | {cells} | "
                  f"{rate:.3f} |")


def release_distances(s, sol, e, eps, periods, seed=1, energy_sign=0):
    """Distances to the orbit at each release; the perturbation is random, or along +-grad E = (K x, M v)."""
    n = s.n
    x0, v0 = np.array(sol.x0), np.array(sol.v0)
    ref = spp.simulate(s, x0, v0, duration=sol.period, restitution=e, sample_times=[sol.period], sample_events=False)
    rel = [ev for ev in ref.events if ev.kind == "release"][0]
    Xr = np.concatenate([rel.x, rel.v_after])
    Xm, _ = mid_flight(s, sol)
    d = np.random.default_rng(seed).standard_normal(2 * n)
    if energy_sign:
        d = energy_sign * np.concatenate([s.K @ Xm[:n], s.M @ Xm[n:]])
    d *= eps * np.linalg.norm(Xm) / np.linalg.norm(d)
    T = periods * sol.period
    r = spp.simulate(s, Xm[:n] + d[:n], Xm[n:] + d[n:], duration=T, restitution=e, sample_times=[T],
                     sample_events=False)
    dist = np.array([np.linalg.norm(np.concatenate([ev.x, ev.v_after]) - Xr) / np.linalg.norm(Xr)
                     for ev in r.events if ev.kind == "release"])
    return dist, r.impacts


def long_runs(cases, laws, eps, periods=1000, energy_sign=0):
    print("| system | SPP (t1, t2) | rho | stable | e | impacts | d_1 | d_10 | d_100 | d_1000 | left at (d > 1e-3) | "
          "measured growth | ")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, s, sol in cases:
        for e in laws:
            dist, impacts = release_distances(s, sol, e, eps, periods, energy_sign=energy_sign)
            cells = [f"{dist[k]:.2e}" if k < dist.size else "-" for k in (0, 9, 99, 999)]
            left = np.flatnonzero(dist > 1e-3)
            # growth per period in the linear range 10 eps < d < 1e-4 (unstable SPPs)
            lin = np.flatnonzero((dist > 10 * eps) & (dist < 1e-4))
            growth = (f"{np.exp(np.polyfit(lin, np.log(dist[lin]), 1)[0]):.4f}" if lin.size > 5 and not sol.stable
                      else "-")
            print(f"| {name} | ({sol.t1:.5f}, {sol.t2:.5f}) | {sol.spectral_radius:.6f} | "
                  f"{'yes' if sol.stable else 'no'} | {e} | {impacts} | " + " | ".join(cells) +
                  f" | {left[0] + 1 if left.size else '-'} | {growth} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--long", action="store_true", help="also the 1000-period simulations")
    ap.add_argument("--eps", type=float, default=1e-10, help="relative perturbation of the long runs")
    ap.add_argument("--energy", type=int, choices=(-1, 0, 1), default=0,
                    help="long runs: perturb along +grad E (1), -grad E (-1) or at random (0)")
    args = ap.parse_args()
    chain = spp.chain(5)
    rod = spp.rod_with_slip()
    two = spp.two_dof()
    c = [x for x in spp.solve(chain, t1_max=12, t2_max=12).solutions if x.admissible]
    r = [x for x in spp.solve(rod, t1_max=12, t2_max=12).solutions if x.admissible]
    t = [x for x in spp.solve(two, t1_max=12, t2_max=12).solutions if x.admissible]
    convergence([("chain5 #0", chain, c[0]), ("chain5 #2", chain, c[2]), ("rod4 #0", rod, r[0]),
                 ("two_dof #0", two, t[0])], [1e-4, 1e-5, 1e-6, 1e-7, 1e-8], [0.0, 0.5, 0.9])
    if args.long:
        print()
        long_runs([(f"chain5 #{i}", chain, x) for i, x in enumerate(c)] + [(f"rod4 #{i}", rod, x) for i, x in enumerate(r)],
                  [0.0, 0.5], args.eps, energy_sign=args.energy)


if __name__ == "__main__":
    main()
