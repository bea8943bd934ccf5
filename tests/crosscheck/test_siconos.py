"""Cross-check of spp against Siconos (Debian python3-siconos), the reference simulator of nonsmooth dynamics.

Siconos integrates the same system, M x'' + K x = w lambda with 0 <= g = w^T x + g0 _|_ lambda >= 0 and Newton's
impact law, with the Moreau-Jean time-stepping scheme (theta = 1/2, LCP at each step). It knows nothing of SPPs:
  * each admissible SPP of the paper's examples (spp solve) must come back after one period in Siconos too, with
    an error that decreases as the step does (first order: the scheme's accuracy at the contact events);
  * spp's exact event-driven simulator and Siconos must agree on a trajectory with impacts and a lasting contact
    phase, to within Siconos' own time-stepping error (estimated from two steps).
The spp command-line tool is given by the SPP_CLI environment variable (CTest sets it).
"""
import csv
import json
import os
import subprocess
import tempfile

import numpy as np
import pytest
import siconos.kernel as sk  # Debian python3-siconos, installed by scripts/install-deps.sh

SRC = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CLI = os.environ.get("SPP_CLI", os.path.join(SRC, "build", "spp"))


def spp(*args):
    return subprocess.run([CLI, *map(str, args)], check=True, capture_output=True, text=True).stdout


def siconos_run(system, x0, v0, duration, steps, restitution=0.0, samples=0):
    """Moreau-Jean over [0, duration] in `steps` steps; returns the final (x, v) and `samples` (t, x) rows."""
    h = duration / steps
    ds = sk.LagrangianLinearTIDS(list(x0), list(v0), np.array(system["M"], dtype=float))
    ds.setKPtr(np.array(system["K"], dtype=float))
    rel = sk.LagrangianLinearTIR(np.array([system["w"]], dtype=float), np.array([system["g0"]], dtype=float))
    inter = sk.Interaction(sk.NewtonImpactNSL(restitution), rel)
    nsds = sk.NonSmoothDynamicalSystem(0.0, duration)
    nsds.insertDynamicalSystem(ds)
    nsds.link(inter, ds)
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(0.5), sk.LCP())
    every = steps // samples if samples else 0
    rows, k = [], 0
    while sim.hasNextEvent():
        sim.computeOneStep()
        sim.nextStep()
        k += 1
        if every and k % every == 0:
            rows.append((k * h, ds.q().copy()))
    return ds.q().copy(), ds.velocity().copy(), rows


def admissible_spps(example, t1_max, t2_max):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "result.json")
        spp("solve", os.path.join(SRC, "examples", example), "--t1-max", t1_max, "--t2-max", t2_max,
            "--admissible-only", "--quiet", "--json", out)
        with open(out) as f:
            result = json.load(f)
    return result["system"], result["solutions"]


@pytest.mark.parametrize("example,t1_max,t2_max,count", [("chain5.json", 12, 12, 7), ("rod4.json", 8, 3, 2)])
def test_every_admissible_spp_returns_in_siconos(example, t1_max, t2_max, count):
    system, solutions = admissible_spps(example, t1_max, t2_max)
    assert len(solutions) == count
    for s in solutions:
        X0 = np.r_[s["x0"], s["v0"]]
        errors = []
        for steps in (4000, 16000):
            x, v, _ = siconos_run(system, s["x0"], s["v0"], s["period"], steps)
            errors.append(np.linalg.norm(np.r_[x, v] - X0) / np.linalg.norm(X0))
        print(f"{example} t1={s['t1']:.6f} t2={s['t2']:.6f}: return error {errors[0]:.2e} (T/4000), "
              f"{errors[1]:.2e} (T/16000)")
        assert errors[0] < 5e-3
        assert errors[1] < errors[0] / 2.5  # at least first order, with margin


def test_exact_simulator_agrees_with_siconos_through_impacts_and_contact():
    system = json.load(open(os.path.join(SRC, "examples", "chain5.json")))
    x0, v0, duration = [0, 0, 0, 0, 0], [0.3, -0.2, 0.5, 0.1, 0.9], 20.0
    with tempfile.TemporaryDirectory() as d:
        traj, events = os.path.join(d, "traj.csv"), os.path.join(d, "events.csv")
        spp("simulate", os.path.join(SRC, "examples", "chain5.json"), "--x0", ",".join(map(str, x0)),
            "--v0", ",".join(map(str, v0)), "--duration", duration, "--restitution", 0, "--samples-per-unit", 10,
            "--csv", traj, "--events", events)
        ours = np.genfromtxt(traj, delimiter=",", names=True)
        kinds = [row["event"] for row in csv.DictReader(open(events))]
    assert kinds.count("impact") >= 2 and kinds.count("contact_onset") >= 1 and kinds.count("release") >= 1

    def distance(rows):
        t = np.array([r[0] for r in rows])
        q = np.array([r[1] for r in rows])
        idx = [int(np.argmin(np.abs(ours["t"] - ti))) for ti in t]
        assert np.max(np.abs(ours["t"][idx] - t)) < 1e-9
        x = np.column_stack([ours[f"x{i}"] for i in range(1, 6)])[idx]
        return np.max(np.abs(q - x)), q

    d_coarse, q_coarse = distance(siconos_run(system, x0, v0, duration, 40000, samples=200)[2])
    d_fine, q_fine = distance(siconos_run(system, x0, v0, duration, 160000, samples=200)[2])
    siconos_error = np.max(np.abs(q_coarse - q_fine))  # Siconos' own error at the coarse step, estimated
    print(f"max |x_spp - x_siconos|: {d_coarse:.2e} (h = T/40000), {d_fine:.2e} (h = T/160000); "
          f"|x_h - x_h/4| in Siconos: {siconos_error:.2e}")
    assert d_fine < d_coarse
    assert d_coarse <= 2.0 * siconos_error
