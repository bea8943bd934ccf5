"""spp.modes (k-IPP families, docs/modes.md) and its frequency-energy figure."""
import math
import os

import matplotlib.image as mpimg
import numpy as np
import pytest

import spp
from spp import plot

SRC = os.environ.get("SPP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_one_dof_backbone_is_the_closed_form():
    # x'' + x = 0 against a stop at g0, e = 1: frequency pi / (pi - arccos(g0 / A)), E = A^2 / 2 (issue 15)
    g0 = 0.5
    s = spp.System(np.eye(1), np.eye(1), [-1.0], g0)
    r = spp.modes(s, k=1, energy_max=4.0)
    assert r.status == "traced"
    (f,) = r.families
    e, freq, margin = f.arrays.T
    amp = np.sqrt(2 * e)
    assert np.allclose(freq, math.pi / (math.pi - np.arccos(g0 / amp)), rtol=1e-10, atol=0)
    assert (margin >= 0).all() and len(e) > 10


def test_points_return_in_the_simulator_with_k_impacts():
    s = spp.two_dof()
    r = spp.modes(s, k=[1, 2, 3], energy_max=3.0)
    checked = 0
    for f in r.families:
        for p in f.points[1::7]:
            if p.margin < 1e-4:
                continue
            sim = spp.simulate(s, p.x0, p.v0, duration=p.period * (1 - 1e-6), restitution=1.0)
            assert sim.impacts == f.k - 1, f.label  # the k-th impact is the return, at t = period
            checked += 1
    assert checked >= 10


def test_modes_figure_draws_backbones_linear_frequencies_and_spps(tmp_path):
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    r = spp.modes(s, k=[1, 2], energy_max=8.0)
    sols = [x for x in spp.solve(s, t1_max=12, t2_max=12).solutions if x.admissible]
    fig = plot.modes_figure(r, sols, path=tmp_path / "modes.png")
    ax = fig.axes[0]
    gids = [ln.get_gid() for ln in ax.lines]
    assert gids.count("linear") == 5
    assert "k1" in gids and "repetition" in gids
    k1 = [ln for ln in ax.lines if ln.get_gid() == "k1"][0]
    e, fr = k1.get_data()
    fam = [f for f in r.families if f.k == 1 and f.multiplicity == 1][0]
    assert np.allclose(e, fam.arrays[fam.arrays[:, 2] >= 0, 0])
    marked = {c.get_gid(): c.get_offsets() for c in ax.collections}
    assert len(marked["admissible"]) == len(sols)
    assert mpimg.imread(tmp_path / "modes.png").shape[2] in (3, 4)


def test_invalid_arguments_raise_value_error():
    s = spp.two_dof()
    with pytest.raises(ValueError, match="k"):
        spp.modes(s, k=0, energy_max=1.0)
    with pytest.raises(ValueError, match="energy_max"):
        spp.modes(s, k=1, energy_max=-1.0)
    with pytest.raises(ValueError, match="g0"):
        spp.modes(spp.two_dof(g0=0.0), k=1, energy_max=1.0)


@pytest.mark.parametrize("k, error", [(1.5, TypeError), ("1..3", TypeError), (None, TypeError), (True, TypeError),
                                      ([1, True], TypeError), (2**63, ValueError), (0, ValueError),
                                      ([1, 41], ValueError)])
def test_bad_k_names_k_and_what_is_expected(k, error):
    # issue 15, D4: 1.5, '1..3', None and 2**63 were pybind11's RuntimeError and True was taken as k = 1
    with pytest.raises(error, match=r"k: expected an int from 1 to 40 or a sequence of them"):
        spp.modes(spp.two_dof(), k=k, energy_max=1.0)


@pytest.mark.parametrize("energy_max", [True, None, "5", [5.0]])
def test_bad_energy_max_type_names_energy_max(energy_max):
    with pytest.raises(TypeError, match=r"^spp.modes: argument energy_max must be float, got "):
        spp.modes(spp.two_dof(), k=1, energy_max=energy_max)


def test_k_as_int_list_range_or_numpy_integers():
    s = spp.two_dof()
    ref = [(f.k, f.label) for f in spp.modes(s, k=[1, 2], energy_max=1.0).families]
    for k in ([1, 2], (1, 2), range(1, 3), np.array([1, 2]), [np.int64(1), 2]):
        assert [(f.k, f.label) for f in spp.modes(s, k=k, energy_max=1.0).families] == ref
    assert spp.modes(s, k=np.int32(1), energy_max=np.float64(1.0)).families[0].k == 1


def test_every_event_kind_reads_as_a_mode_event_kind():
    # chain5, k = 1..3: families past a flight grazing start with a grazing_continuation event, which was missing from
    # the Python enum (reading e.kind raised "'grazing_continuation' is not a valid ModeEventKind")
    r = spp.modes(spp.chain(5), [1, 2, 3], 6.0)
    kinds = {str(e.kind) for f in r.families for e in f.events}
    assert "grazing_continuation" in kinds
    assert {"grazing_start", "branch_point", "energy_max"} <= kinds
    assert all(isinstance(e.kind, spp.ModeEventKind) for f in r.families for e in f.events)


# Issue 13: ModesResult, ModeFamily, ModePoint and ModeEvent printed as <spp._spp.ModesResult object at 0x...>, could
# not be pickled (a process pool returning families failed) and had no DataFrame, unlike the other result types.
def test_modes_results_show_themselves_pickle_and_make_frames():
    import html
    import pickle
    s = spp.two_dof()
    r = spp.modes(s, k=[1, 2], energy_max=3.0)
    i = next(i for i, x in enumerate(r.families) if x.events)
    f = r.families[i]
    p, e = f.points[len(f.points) // 2], f.events[0]
    assert repr(r) == "<spp.ModesResult " + r.brief_report()[len("spp modes: "):] + ">"
    assert repr(f).startswith(f"<spp.ModeFamily {f.label}: k={f.k} {f.symmetry} mode={f.mode}")
    assert f"{len(f.points)} points" in repr(f) and str(e.kind) in repr(f)
    assert repr(p).startswith(f"<spp.ModePoint energy={p.energy:g}") and f"{len(p.impact_times)} impacts" in repr(p)
    assert repr(e).startswith(f"<spp.ModeEvent {e.kind} at energy=")
    for x in (r, f, p, e):
        assert x._repr_html_().startswith("<p>" + html.escape(repr(x)) + "</p>"), type(x)
    back = pickle.loads(pickle.dumps(r))
    assert type(back) is type(r) and back.status == r.status and back.interrupted == r.interrupted
    assert back.corrector_solves == r.corrector_solves and back.seconds == r.seconds
    assert np.array_equal(back.linear_frequencies, r.linear_frequencies)
    assert len(back.families) == len(r.families) and repr(back) == repr(r)
    for a, b in zip(r.families, back.families):
        assert (a.k, a.symmetry, a.mode, a.multiplicity, a.label) == (b.k, b.symmetry, b.mode, b.multiplicity, b.label)
        assert np.array_equal(a.arrays, b.arrays)
        events = [[(x.kind, x.detail, x.at.energy) for x in y.events] for y in (a, b)]
        assert events[0] == events[1]
        for x, y in zip(a.points, b.points):
            for name in ("energy", "period", "frequency", "impact_times", "x0", "v0", "admissible", "margin",
                         "multiplicity"):
                assert np.array_equal(getattr(x, name), getattr(y, name)), name
    for x in (f, p, e):
        assert repr(pickle.loads(pickle.dumps(x))) == repr(x)
    pd = pytest.importorskip("pandas")
    df = r.to_dataframe()
    assert list(df.columns) == ["family", "label", "k", "symmetry", "mode", "family_multiplicity", "energy",
                                "frequency", "period", "impacts", "admissible", "margin", "multiplicity"]
    assert len(df) == sum(len(x.points) for x in r.families) and df["admissible"].dtype == bool
    rows = df[df["family"] == i]
    assert np.array_equal(rows[["energy", "frequency", "margin"]].to_numpy(), f.arrays)
    assert (rows["impacts"] == f.k).all() and (rows["label"] == f.label).all()
    ff = f.to_dataframe()
    assert list(ff.columns) == list(df.columns[6:]) and np.array_equal(ff[["energy", "frequency", "margin"]], f.arrays)
    assert "<table" in r._repr_html_() and isinstance(ff, pd.DataFrame)


def test_multiples_follows_one_ipp_families_from_grazing_orbits_at_period_multiples():
    # issue 15: spp modes --multiples J existed in the CLI only. On the 2-dof of §2.3 the admissible 1-IPP branch of
    # T in [5.607, 7.766] leaves mode 2's grazing orbit seen with twice its period (tests/modes, C++: the same check)
    s = spp.two_dof()

    def covers(r, lo, hi):
        return any(p.admissible and p.margin > 1e-6 and lo < p.period < hi for f in r.families for p in f.points)

    assert not covers(spp.modes(s, k=1, energy_max=20.0), 5.62, 7.75)
    r = spp.modes(s, k=1, energy_max=20.0, multiples=5)
    assert covers(r, 5.62, 7.75) and covers(r, 18.36, 19.41)
    labels = [f.label for f in r.families]
    assert [f.label for f in spp.modes(s, k=1, energy_max=20.0, multiples=np.int64(5)).families] == labels


@pytest.mark.parametrize("multiples, error", [(2.0, TypeError), ("3", TypeError), (None, TypeError),
                                              (True, TypeError), (0, ValueError), (101, ValueError),
                                              (2**63, ValueError)])
def test_bad_multiples_names_multiples_and_what_is_expected(multiples, error):
    with pytest.raises(error, match=r"multiples: expected an int from 1 to 100"):
        spp.modes(spp.two_dof(), k=1, energy_max=1.0, multiples=multiples)


def test_through_inadmissible_reaches_the_stretches_beyond_an_admissibility_event():
    # chain5, E <= 5, multiples 13: T in [12.23, 13.04] is an admissible 1-IPP stretch separated from every seed by
    # inadmissible orbits (tests/crosscheck/modes_one_ipp_scan.py); followed through them, a family starts there
    s = spp.chain(5)
    def covers(r):
        return [f.label for f in r.families if any(p.admissible and 12.3 < p.period < 13.0 for p in f.points)]
    assert covers(spp.modes(s, 1, 5.0, multiples=13)) == []
    r = spp.modes(s, 1, 5.0, multiples=13, through_inadmissible=True)
    assert len(covers(r)) == 1 and r.inadmissible_stretches > 0
    first = [f.events[0].kind for f in r.families]
    assert spp.ModeEventKind.admissibility_regained in first
    with pytest.raises(TypeError, match="through_inadmissible"):
        spp.modes(s, 1, 5.0, through_inadmissible="yes")


# Every C++ value of a result enum is bound (enumerated from C++, no hand-written list: ModeEventKind lacked
# grazing_continuation before); an interrupted family ends with its own kind `interrupted`, not `stalled`.
def test_result_enums_have_every_cpp_value():
    expected = {
        "ContinuationStatus": ["success", "incomplete"],
        "BranchEventKind": ["leaves_window", "range_end", "fold", "admissibility_lost", "admissibility_gained",
                            "gap_closure", "closed_loop", "stalled", "stability_lost", "stability_gained"],
        "MultiplierCrossing": ["none", "plus_one", "minus_one", "complex_pair"],
        "ModeEventKind": ["grazing_start", "branch_start", "grazing_continuation", "branch_point", "impact_grazing",
                          "flight_grazing", "energy_max", "stalled", "no_admissible_side", "admissibility_regained",
                          "interrupted", "closed_loop", "seeded"],
        "ModesStatus": ["not run", "traced", "incomplete"],
        "SolveStatus": ["not_run", "success", "incomplete"],
        "SimulationStatus": ["not_run", "success", "event_limit", "stalled", "interrupted"],
        "EventKind": ["impact", "contact_onset", "release"],
        "VerifyStatus": ["success", "inconsistent", "interrupted", "incomplete"],
        "Verdict": ["returns", "leaves"],
        "StabilityVerdict": ["not_computed", "stable", "unstable", "undecided", "neutral"],
    }
    for name, values in expected.items():
        assert [m.value for m in getattr(spp._spp, name)] == values, name


# Issue 15: modes reported no progress (2-dof k = 1..12: 89 s silent). progress=f is called with a ModesProgress
# (every 0.2 s, as solve's callback); returning False stops the tracing with the families traced so far.
def test_progress_callable_sees_modes_progress_and_can_stop_it():
    s = spp.two_dof(1, 1, 1, 1, 1)
    seen = []

    def report(p):
        seen.append(p)
        return len(seen) < 3

    r = spp.modes(s, k=range(1, 13), energy_max=20, progress=report)
    assert len(seen) == 3
    assert all(isinstance(p, spp.ModesProgress) for p in seen)
    assert seen[-1].k_last == 12 and 1 <= seen[-1].k <= 12 and seen[-1].seconds >= 0.4
    assert "tracing k = " in seen[-1].line() and "tracing k = " in repr(seen[-1])
    assert r.interrupted and r.status == "incomplete"
    with pytest.raises(TypeError, match="progress"):
        spp.modes(s, k=1, energy_max=1, progress=5)


# Issue 15: seed_period_max seeds families from the plane of the two flight durations (spp modes --seed-period-max).
def test_seed_period_max_adds_seeded_families():
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    plain = spp.modes(s, k=2, energy_max=2.0)
    seeded = spp.modes(s, k=2, energy_max=2.0, seed_period_max=40)
    kinds = [e.kind for f in seeded.families for e in f.events]
    seed = spp.ModeEventKind.seeded
    assert seed not in [e.kind for f in plain.families for e in f.events]
    assert kinds.count(seed) >= 3
    assert all(f.mode == 0 for f in seeded.families if any(e.kind == seed for e in f.events))
    with pytest.raises(ValueError, match="seed_period_max"):
        spp.modes(s, k=2, energy_max=2.0, seed_period_max=-1)
