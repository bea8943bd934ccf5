"""Floquet multipliers from Python (docs/stability.md): Solution fields, spp.monodromy, the simulator's finite
differences, and the result file's round trip."""
import math
import os
import pickle
import sys

import numpy as np
import pytest

import spp

SRC = os.environ.get("SPP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(SRC, "tests", "crosscheck"))
from floquet_convergence import fd_monodromy, mid_flight  # noqa: E402


@pytest.fixture(scope="module")
def chain():
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    return s, spp.solve(s, t1_max=12, t2_max=12, admissible_only=True)


def test_every_admissible_spp_carries_its_multipliers(chain):
    s, r = chain
    for sol in r.solutions:
        mu = sol.floquet_multipliers
        assert mu.shape == (2 * s.n,) and mu.dtype == np.complex128
        assert np.all(np.diff(np.abs(mu)) >= 0)  # sorted by modulus
        assert np.sum(np.abs(mu) < 1e-10) == 2  # the onset's projection
        assert np.sum(mu == 1.0) >= 2  # flow direction and energy
        assert sol.stability_margin == pytest.approx(1.0 - sol.spectral_radius, abs=0.0)
        # the verdict (docs/stability.md §2): decided on every chain SPP, by a rounding bound far below |rho - 1|
        assert sol.stability_verdict in (spp.StabilityVerdict.stable, spp.StabilityVerdict.unstable)
        assert 0.0 < sol.spectral_radius_error < 1e-9
        assert (sol.stability_verdict == "stable") == (sol.spectral_radius + sol.spectral_radius_error < 1.0)
        assert sol.stable == (sol.admissible and sol.stability_verdict == "stable")
        lead = sol.leading_multipliers
        assert len(lead) in (1, 2) and abs(lead[0]) == sol.spectral_radius
        assert len(lead) == 1 or lead[1] == np.conj(lead[0])
        mono, x0, v0, period = spp.monodromy(s, sol.t1, sol.t2)
        assert np.allclose(x0, sol.x0, atol=1e-10) and period == pytest.approx(sol.period)
        full = np.linalg.eigvals(mono)
        for m in mu:
            tol = 1e-6 if abs(m - 1.0) < 1e-3 else 1e-8  # the Jordan block at 1
            assert np.min(np.abs(full - m)) < tol


def test_finite_differences_of_the_simulator_agree(chain):
    s, r = chain
    sol = r.solutions[2]  # stable, rho = 0.98576
    Xm, mono_mid = mid_flight(s, sol)
    errs = [np.linalg.norm(fd_monodromy(s, Xm, sol.period, 0.5, d) - mono_mid) / np.linalg.norm(mono_mid)
            for d in (1e-5, 1e-8)]
    assert errs[1] < 0.1
    assert 5.0 < errs[0] / errs[1] < 20.0  # delta^(1/3): a factor 10 over three decades


def test_result_file_round_trip_and_switch(chain):
    s, r = chain
    back = pickle.loads(pickle.dumps(r))  # a SolveResult pickles as its result file's JSON text
    assert len(back.solutions) == len(r.solutions)
    for a, b in zip(r.solutions, back.solutions):
        assert np.array_equal(a.floquet_multipliers, b.floquet_multipliers)
        assert a.spectral_radius == b.spectral_radius and a.stable == b.stable
        assert a.stability_verdict == b.stability_verdict and a.spectral_radius_error == b.spectral_radius_error
    off = spp.solve(s, t1_max=7, t2_max=1, admissible_only=True, compute_stability=False)
    assert off.solutions and math.isnan(off.solutions[0].spectral_radius)
    assert off.solutions[0].floquet_multipliers.size == 0 and not off.solutions[0].stable
    assert off.solutions[0].stability_verdict is spp.StabilityVerdict.not_computed


def test_figures_mark_stability(chain, tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from spp import plot
    s, r = chain
    fig = plot.multipliers_figure(r.solutions, path=tmp_path / "mu.png")
    drawn = {c.get_gid(): c for c in fig.axes[0].collections}
    for k, sol in enumerate(r.solutions):
        mu = sol.floquet_multipliers
        off = drawn[f"spp_{k}"].get_offsets()
        assert np.allclose(off[:, 0] + 1j * off[:, 1], mu)
        assert (len(drawn[f"spp_{k}"].get_facecolors()) > 0 and drawn[f"spp_{k}"].get_facecolors()[0][3] > 0) == sol.stable
    x, y = fig.axes[0].lines[0].get_data()
    assert np.allclose(np.hypot(x, y), 1.0)  # the unit circle
    fe = plot.frequency_energy_figure(r.solutions)
    marked = {c.get_gid(): c.get_offsets() for c in fe.axes[0].collections}
    want = np.array([(x.energy, 2 * np.pi / x.period) for x in r.solutions if x.stable])
    assert len(want) == 2 and np.allclose(np.sort(marked["stable"], axis=0), np.sort(want, axis=0))
    plt.close("all")


def test_continuation_event_names_the_multiplier_that_crosses():
    # the chain with k5 as parameter (tests/continuation): its SPP near (5.707, 2.510) gains stability at
    # k5 = 0.983578 through +1; checked here on numpy's eigenvalues of the physical monodromy 1e-4 on either side
    # (one real eigenvalue beyond 1 + 1e-6 on the unstable side, none on the stable one; the structural Jordan block
    # at 1 splits by ~1e-8 only)
    K0 = np.array([[2., -1, 0, 0, 0], [-1, 2, -1, 0, 0], [0, -1, 2, -1, 0], [0, 0, -1, 1, 0], [0, 0, 0, 0, 0]])
    K1 = np.zeros((5, 5))
    K1[3:, 3:] = [[1, -1], [-1, 1]]
    w = np.array([0., 0, 0, 0, -1])
    ps = spp.ParametricSystem(np.eye(5), np.zeros((0, 0)), K0, K1, w, np.zeros(0), 1.0, "k5", 0.9, 1.0)
    sols = spp.solve(ps.at(0.98), t1_max=8, t2_max=3).solutions
    sol = min(sols, key=lambda s: math.hypot(s.t1 - 5.703374, s.t2 - 2.514785))
    r = spp.continue_branch(ps, 0.98, sol, t1_max=8, t2_max=3)
    kinds = (spp.BranchEventKind.stability_lost, spp.BranchEventKind.stability_gained)
    events = [e for e in r.branches[0].events if e.kind in kinds]
    assert len(events) == 1
    e = events[0]
    assert all(x.crossing is spp.MultiplierCrossing.none for x in r.branches[0].events if x.kind not in kinds)
    assert e.crossing is spp.MultiplierCrossing.plus_one and e.crossing_angle == 0.0
    assert e.crossing_multipliers.shape == (1,) and abs(e.crossing_multipliers[0] - 1.0) < 1e-6
    assert "through +1" in e.detail

    def beyond(mu):
        mono = spp.monodromy(ps.at(mu), e.at.t1, e.at.t2)[0]
        ev = np.linalg.eigvals(mono)
        return ev[np.abs(ev) > 1.0 + 1e-6]

    out = [beyond(e.at.mu - 1e-4), beyond(e.at.mu + 1e-4)]
    assert sorted(len(o) for o in out) == [0, 1]
    z = max(out, key=len)[0]
    assert abs(z.imag) < 1e-9 and z.real > 1.0


def test_leading_multipliers_survive_load_result(chain, tmp_path):
    # found by the attack of issue 14: present after solve and pickle, [] after load_result
    s, r = chain
    path = str(tmp_path / "c5.json")
    with open(path, "w") as f:
        f.write(r.to_json())
    back = spp.load_result(path)
    assert len(back.solutions) == len(r.solutions)
    for a, b in zip(r.solutions, back.solutions):
        assert len(b.leading_multipliers) == len(a.leading_multipliers) > 0
        assert np.allclose(b.leading_multipliers, a.leading_multipliers, rtol=1e-12, atol=0)


def test_dataframe_has_the_csv_columns(chain, tmp_path):
    # found by the attack of issue 14: to_dataframe lacked spectral_radius_error and stability_verdict; names only
    # (how the CSV writes booleans may change), in the CSV's order, then flags
    pytest.importorskip("pandas")
    import subprocess
    cli = os.path.join(os.path.dirname(spp.__file__), "..", "..", "spp")  # build/python/spp -> build/spp
    if not os.path.exists(cli):
        pytest.skip("the spp command is not built beside the package")
    s, r = chain
    csv = tmp_path / "c5.csv"
    subprocess.run([cli, "solve", os.path.join(SRC, "examples", "chain5.json"), "--t1-max", "12", "--t2-max", "12",
                    "--csv", str(csv)], check=True, capture_output=True)
    header = csv.read_text().splitlines()[0].split(",")
    assert list(r.to_dataframe().columns) == header + ["flags"]
