"""Figures: files are valid images of the expected size, and the plotted data are the solver's."""
import os

import matplotlib
import matplotlib.image as mpimg
import numpy as np

import spp
from spp import plot

SRC = os.environ.get("SPP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def result():
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    return s, spp.solve(s, t1_max=12, t2_max=12)


def test_spp_figure_png_and_svg(tmp_path):
    s, r = result()
    sol = [x for x in r.solutions if x.admissible][0]
    fig = plot.spp_figure(s, sol, path=tmp_path / "spp.png")
    plot.spp_figure(s, sol, path=tmp_path / "spp.svg")
    img = mpimg.imread(tmp_path / "spp.png")
    assert img.shape[0] > 600 and img.shape[1] > 1000
    assert (tmp_path / "spp.svg").read_text().lstrip().startswith("<?xml")
    top = fig.axes[0]
    gap = top.lines[2]  # after the two symmetry axes
    t, g = gap.get_data()
    assert t.min() >= -2 * sol.t1 - 1e-12 and t.max() <= 2 * sol.t2 + 1e-12
    assert g.min() > -1e-9  # admissible: the gap never goes negative



def test_spp_figure_draws_the_zero_gap_spp_of_section_6_1(tmp_path):
    # README's Fig. 8 command failed with "g0 = 0 ..." once spp_figure took its curves from trajectory, which cannot
    # re-solve a zero-gap SPP at one parameter value: those come from the simulator, started at the onset state
    ps = spp.ParametricSystem.from_json(os.path.join(SRC, "examples", "two_dof_zero_gap.json"))
    p = spp.continue_branches(ps, t1_max=3, t2_max=1).gap_closures()[1]
    fig = plot.spp_figure(ps.at(p.mu), p, path=tmp_path / "fig8.png")
    t, g = fig.axes[0].lines[2].get_data()
    assert t.min() >= -2 * p.t1 - 1e-12 and t.max() <= 2 * p.t2 + 1e-12
    assert g.min() > -1e-9 and abs(g[np.argmin(np.abs(t))]) < 1e-9  # admissible, gap closed at onset (g0 = 0)
    contact = (t > 1e-9) & (t < 2 * p.t2 - 1e-9)
    assert np.abs(g[contact]).max() < 1e-9  # and held closed through the contact phase

def test_frequency_energy_marks_the_solutions(tmp_path):
    _, r = result()
    fig = plot.frequency_energy_figure(r.solutions, path=tmp_path / "fe.png")
    marked = {c.get_gid(): c.get_offsets() for c in fig.axes[0].collections}
    adm = np.array([(x.energy, 2 * np.pi / x.period) for x in r.solutions if x.admissible])
    assert np.allclose(np.sort(marked["admissible"], axis=0), np.sort(adm, axis=0))
    assert len(marked["potential"]) == 57
    assert mpimg.imread(tmp_path / "fe.png").shape[2] in (3, 4)


def test_root_map_marks_the_solutions_and_draws_both_conditions(tmp_path):
    s, r = result()
    window = dict(t1_min=r.t1_min, t1_max=r.t1_max, t2_min=r.t2_min, t2_max=r.t2_max)
    fig = plot.root_map_figure(s, r.solutions, window, points=120, path=tmp_path / "rm.png")
    ax = fig.axes[0]
    marked = {c.get_gid(): c.get_offsets() for c in ax.collections if c.get_gid()}
    adm = np.array([(x.t1, x.t2) for x in r.solutions if x.admissible])
    pot = np.array([(x.t1, x.t2) for x in r.solutions if not x.admissible])
    assert np.allclose(np.sort(marked["admissible"], axis=0), np.sort(adm, axis=0))
    assert np.allclose(np.sort(marked["potential"], axis=0), np.sort(pot, axis=0))
    # Every SPP lies on a drawn curve of (5.1a): the nearest vertex of the solid contours is within a grid step.
    solid = [seg for c in ax.collections if not c.get_gid() and hasattr(c, "get_paths")
             and np.allclose(c.get_edgecolor()[0][:3], matplotlib.colors.to_rgb("C0"))
             for p in c.get_paths() for seg in [p.vertices] if len(seg)]
    vertices = np.vstack(solid)
    step = 12.0 / 119
    for t1, t2 in np.vstack([adm, pot]):
        assert np.hypot(vertices[:, 0] - t1, vertices[:, 1] - t2).min() < 2 * step
    img = mpimg.imread(tmp_path / "rm.png")
    assert img.shape[0] > 700 and img.shape[1] > 700


def test_root_map_cells_match_the_solver_window():
    s, r = result()
    rm = spp.root_map(s, 12.0, 12.0, t1_points=40, t2_points=40)
    assert len(rm.cells) == (len(rm.flight_poles) + 1) * (len(rm.contact_poles) + 1)
    for c in rm.cells:
        assert c.symmetric.shape == (len(c.t2), len(c.t1)) == c.onset.shape
    try:
        spp.root_map(s, -1.0, 12.0)
    except ValueError as e:
        assert "t1_max" in str(e)
    else:
        raise AssertionError("expected ValueError")


def test_importing_the_figure_modules_keeps_the_backend():
    # A notebook's inline backend (here: svg, chosen first) must survive `import spp.plot` / `spp.animate`.
    import subprocess
    import sys
    code = ("import matplotlib; matplotlib.use('svg'); import spp.plot, spp.animate; "
            "print(matplotlib.get_backend())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "svg"


def test_figures_draw_into_given_axes():
    import matplotlib.pyplot as plt
    s, r = result()
    fig, ax = plt.subplots()
    assert plot.frequency_energy_figure(r.solutions, ax=ax) is fig
    assert {c.get_gid() for c in ax.collections} == {"admissible", "potential", "stable"}  # stable: ringed (docs/stability.md)
    fig2, (top, bottom) = plt.subplots(2, 1)
    sol = [x for x in r.solutions if x.admissible][0]
    assert plot.spp_figure(s, sol, axes=(top, bottom)) is fig2
    # the force on its own (twin) axis, the gap on the top one
    twins = [a for a in fig2.axes if a not in (top, bottom)]
    assert len(twins) == 1 and twins[0].lines[0].get_label().startswith("contact force")
    assert top.lines[2].get_label().startswith("gap")
    plt.close("all")


def test_positions_past_ten_dofs_use_a_colour_map():
    import matplotlib.pyplot as plt
    s = spp.chain(12)
    r = spp.solve(s, t1_max=3, t2_max=3)
    assert r.solutions
    fig = plot.spp_figure(s, r.solutions[0])
    bottom = fig.axes[1]
    colors = [tuple(line.get_color()) for line in bottom.lines[2:]]  # after the two symmetry axes
    assert len(colors) == 12 and len(set(colors)) == 12
    assert bottom.get_legend() is None and any(a.get_label() == "<colorbar>" for a in fig.axes)
    plt.close("all")


def test_root_map_takes_a_result_or_a_tuple_as_window():
    import matplotlib.pyplot as plt
    import pytest
    s, r = result()
    a = plot.root_map_figure(s, r.solutions, r, points=40)
    b = plot.root_map_figure(s, r.solutions, (r.t1_min, r.t1_max, r.t2_min, r.t2_max), points=40)
    assert a.axes[0].get_xlim() == b.axes[0].get_xlim() == (r.t1_min, r.t1_max)
    with pytest.raises(ValueError, match="expected a dict with t1_min"):
        plot.root_map_figure(s, r.solutions, (1, 2), points=40)
    plt.close("all")


def test_plot_command_draws_the_chosen_solutions(tmp_path):
    from spp.__main__ import main
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    r = spp.solve(s, t1_max=12, t2_max=12)
    res = tmp_path / "r.json"
    res.write_text(r.to_json(s))
    out = tmp_path / "figs"
    main(["plot", str(res), "--out", str(out), "--solutions", "0,3", "--root-map-points", "0", "--formats", "png"])
    assert sorted(os.listdir(out)) == ["frequency_energy.png", "spp_0.png", "spp_3.png"]
    admissible = [k for k, x in enumerate(r.solutions) if x.admissible]
    main(["plot", str(res), "--out", str(tmp_path / "adm"), "--root-map-points", "0", "--formats", "png"])
    assert sorted(os.listdir(tmp_path / "adm")) == sorted(["frequency_energy.png"] + [f"spp_{k}.png" for k in admissible])
    assert main(["plot", str(res), "--out", str(tmp_path / "none"), "--solutions", "64"]) == 1  # (0..63)
    assert main(["plot", str(res), "--out", str(tmp_path / "none"), "--solutions", "1,x"]) == 1
    assert not (tmp_path / "none").exists()


def test_plot_command_failing_half_way_leaves_no_partial_set(tmp_path, monkeypatch, capsys):
    # a failure after some figures were drawn left them behind beside older ones (found by an independent attack):
    # the figures are now staged and moved in only when all are drawn; the message names the result file
    from spp.__main__ import main
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    r = spp.solve(s, t1_max=12, t2_max=12)
    res = tmp_path / "r.json"
    res.write_text(r.to_json(s))
    out = tmp_path / "figs"
    out.mkdir()
    (out / "spp_3.png").write_bytes(b"older figure")
    drawn = []
    real = plot.spp_figure

    def failing(system, solution, **kw):
        drawn.append(solution)
        if len(drawn) == 2:
            raise ValueError("K must be positive definite (a stand-in for a refusal half-way)")
        return real(system, solution, **kw)

    monkeypatch.setattr(plot, "spp_figure", failing)
    code = main(["plot", str(res), "--out", str(out), "--solutions", "0,3", "--root-map-points", "0",
                 "--formats", "png"])
    assert code == 1
    assert len(drawn) == 2
    assert sorted(os.listdir(out)) == ["spp_3.png"]  # nothing new, no staging directory left
    assert (out / "spp_3.png").read_bytes() == b"older figure"
    assert f"{res}: K must be positive definite" in capsys.readouterr().err
    fresh = tmp_path / "fresh"
    drawn.clear()
    assert main(["plot", str(res), "--out", str(fresh), "--solutions", "0,3", "--root-map-points", "0",
                 "--formats", "png"]) == 1
    assert not fresh.exists()
