"""Figures: files are valid images of the expected size, and the plotted data are the solver's."""
import os

import matplotlib
import matplotlib.image as mpimg
import numpy as np
import pytest

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
    step = 1.5 * 12.0 / 119  # the 120 points per axis include each of the 23 cells' two ends (not 120 + 23 of them)
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


# Found by an independent attack on issue 13: a notebook redraw of a root map sampled it again (a 20-dof box: a
# minute). root_map_figure(..., computed=rm) draws a map already computed, sampling nothing.
def test_root_map_figure_draws_a_computed_map_without_sampling(tmp_path, monkeypatch):
    import pytest
    s, r = result()
    rm = spp.root_map(s, 12, 12, t1_points=60, t2_points=60)

    def refused(*args, **kw):
        raise AssertionError("sampled again")

    monkeypatch.setattr(plot, "root_map", refused)
    fig = plot.root_map_figure(s, r.solutions, r, computed=rm, path=tmp_path / "rm.png")
    assert len(fig.axes[0].collections) >= 2  # both conditions' contours, from the given map
    assert [ln.get_xdata()[0] for ln in fig.axes[0].lines[:len(rm.flight_poles)]] == list(rm.flight_poles)
    with pytest.raises(TypeError, match="computed must be a RootMap"):
        plot.root_map_figure(s, r.solutions, r, computed="rm")
    matplotlib.pyplot.close("all")


# Found by an independent attack on issue 13: --solutions 0,0 drew spp_0 twice, failed moving the second in ("No
# such file or directory") and left frequency_energy.png and spp_0.png behind. A repeated index is refused first.
def test_plot_command_refuses_a_repeated_solution_index_and_leaves_nothing(tmp_path, capsys):
    from spp.__main__ import main
    s, r = result()
    res = tmp_path / "r.json"
    res.write_text(r.to_json(s))
    out = tmp_path / "figs"
    assert main(["plot", str(res), "--out", str(out), "--solutions", "0,3,0", "--root-map-points", "0",
                 "--formats", "png"]) == 1
    assert "expected each index once, got 0 more than once" in capsys.readouterr().err
    assert not out.exists()


# Found by the same attack: python3 -m spp --version, an unknown subcommand or option exited 2 (argparse's code) while
# README says a usage error exits 1, as in every other spp subcommand.
def test_usage_errors_of_python_m_spp_exit_1(capsys):
    from spp.__main__ import main
    assert main(["--version"]) == 1
    assert main(["foo"]) == 1
    assert main(["plot", "--bogus"]) == 1
    assert main(["--help"]) == 0
    assert "usage:" in capsys.readouterr().out


# Found by an independent attack on issue 13: the root map of an interrupted result did not show the part of the window
# that was never searched (an empty region looked like one without SPPs).
def test_root_map_shades_the_unsearched_region_of_an_interrupted_result(tmp_path):
    s = spp.chain(10)  # its box: a search of seconds, stopped at its first report
    t1, t2 = spp.fundamental_box(s)
    r = spp.solve(s, t1_max=t1, t2_max=t2, progress=lambda p: False)
    assert r.status == "incomplete" and any(u["cause"] == "interrupted" for u in r.uncertified)
    fig = plot.root_map_figure(s, r.solutions, r, points=40, path=tmp_path / "rm.png")
    ax = fig.axes[0]
    shaded = [c for c in ax.collections if c.get_gid() == "uncertified_interrupted"]
    assert len(shaded) == 1
    regions = [u for u in r.uncertified if u["cause"] == "interrupted"]
    assert len(shaded[0].get_paths()) == len(regions)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(lab.startswith("not searched (interrupted)") for lab in labels), labels
    # counted in cells, as the run reports them (it counted the merged rectangles; found by an attack on issue 13)
    assert f"not searched (interrupted): {r.stats['unsearched_cells']} cells" in labels, labels
    # the regions given explicitly (a window as a dict) are shaded as well; none without them
    w = dict(t1_min=r.t1_min, t1_max=r.t1_max, t2_min=r.t2_min, t2_max=r.t2_max)
    fig2 = plot.root_map_figure(s, r.solutions, w, points=40, uncertified=r.uncertified)
    assert any(c.get_gid() == "uncertified_interrupted" for c in fig2.axes[0].collections)
    fig3 = plot.root_map_figure(s, r.solutions, w, points=40)
    assert not any(str(c.get_gid()).startswith("uncertified") for c in fig3.axes[0].collections)


# Found by the same attack: the root map's markers carried no number, so an SPP of the table could not be found on it;
# and the legend lay over the map.
def test_root_map_numbers_the_spps_as_the_table_and_keeps_the_legend_outside(tmp_path):
    s, r = result()
    fig = plot.root_map_figure(s, r.solutions, r, points=60, path=tmp_path / "rm.png")
    ax = fig.axes[0]
    numbers = [t for t in ax.texts if t.get_gid() == "spp_number"]
    assert [t.get_text() for t in numbers] == [str(k) for k in range(len(r.solutions))]
    assert min(t.get_fontsize() for t in numbers) >= 6  # 5 was unreadable at the column width (attack on issue 13)
    for t, sol in zip(numbers, r.solutions):
        assert np.allclose(t.xy, (sol.t1, sol.t2))
    fig.canvas.draw()
    legend = ax.get_legend().get_window_extent()
    axes = ax.get_window_extent()
    assert legend.y1 <= axes.y0 or legend.x0 >= axes.x1  # below or beside the axes, not over the map
    assert not plot.root_map_figure(s, r.solutions, r, points=30, numbers=False).axes[0].texts


def test_spp_figure_legend_lies_outside_the_curves(tmp_path):
    s, r = result()
    fig = plot.spp_figure(s, r.solutions[3], path=tmp_path / "s.png")
    fig.canvas.draw()
    top = fig.axes[0]
    legend = top.get_legend().get_window_extent()
    assert legend.x0 >= top.get_window_extent().x1


# Found by the same attack: Ctrl-C in `spp plot` printed a 47-line Python traceback. Now one line, exit 130, and no
# figure (nor the output directory it created) left behind.
def test_ctrl_c_in_plot_command_prints_one_line_and_leaves_nothing(tmp_path):
    import signal
    import subprocess
    import sys
    import time
    s = spp.chain(10)  # its box: a search of seconds, stopped at its first report
    t1, t2 = spp.fundamental_box(s)
    r = spp.solve(s, t1_max=t1, t2_max=t2, progress=lambda p: False)
    res = tmp_path / "r.json"
    res.write_text(r.to_json(s))
    out = tmp_path / "figs"
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    p = subprocess.Popen([sys.executable, "-m", "spp", "plot", str(res), "--out", str(out), "--root-map-points",
                          "4000", "--formats", "png"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=env)
    deadline = time.monotonic() + 60
    while not out.exists() and time.monotonic() < deadline and p.poll() is None:  # the root map is being drawn
        time.sleep(0.05)
    time.sleep(1.0)
    p.send_signal(signal.SIGINT)
    stdout, stderr = p.communicate(timeout=60)
    assert p.returncode == 130, (p.returncode, stderr)
    assert stderr == "interrupted\n", stderr
    assert stdout == ""
    assert not out.exists()


def test_frequency_energy_legend_covers_no_spp(tmp_path):
    # chain5's SPP #0 (E = 20, f = 0.956) was hidden under the legend placed inside the axes by loc="best".
    _, r = result()
    fig = plot.frequency_energy_figure(r.solutions, path=tmp_path / "fe.png")
    fig.canvas.draw()
    ax = fig.axes[0]
    box = ax.get_legend().get_window_extent()
    pts = ax.transData.transform([(x.energy, 2 * np.pi / x.period) for x in r.solutions])
    inside = [k for k, (u, v) in enumerate(pts) if box.x0 <= u <= box.x1 and box.y0 <= v <= box.y1]
    assert inside == []
    assert box.x0 >= 0 and box.y0 >= 0 and box.x1 <= fig.bbox.x1  # and on the figure, not cut off


# Issue 13: spp_figure, which makes two axes, could be given its axes but not a figure; no function took fig=.
# Every figure function now fills a Figure it is given (cleared first, its size kept) and returns it.
def test_every_figure_function_fills_a_given_figure():
    import matplotlib.pyplot as plt
    s, r = result()
    sol = [x for x in r.solutions if x.admissible][0]
    fig = plt.figure(figsize=(9, 5))
    fig.add_subplot().plot([0, 1])  # what was there is cleared
    assert plot.spp_figure(s, sol, fig=fig) is fig
    assert len(fig.axes) == 3 and tuple(fig.get_size_inches()) == (9, 5)  # gap, positions, the force's twin
    assert fig.axes[0].lines[2].get_label().startswith("gap")
    m = spp.modes(spp.two_dof(), k=1, energy_max=2.0)
    for draw in (lambda f: plot.frequency_energy_figure(r.solutions, fig=f),
                 lambda f: plot.multipliers_figure(r.solutions, fig=f),
                 lambda f: plot.modes_figure(m, r.solutions, fig=f),
                 lambda f: plot.root_map_figure(s, r.solutions, (0, 3, 0, 3), points=40, fig=f)):
        fig = plt.figure(figsize=(4, 3))
        old = fig.add_subplot()
        assert draw(fig) is fig and len(fig.axes) == 1 and fig.axes[0] is not old
    other = plt.figure()
    with pytest.raises(ValueError, match="expected ax in fig"):
        plot.frequency_energy_figure(r.solutions, ax=other.add_subplot(), fig=plt.figure())
    plt.close("all")


# Issue 13: the root map's SPP numbers, each up right of its marker, overlapped on the paper's chain (12/14, 35/40,
# 46/48 in (0, 12]^2). Each is now placed where it overlaps no other number and no other marker.
def test_root_map_numbers_do_not_overlap_each_other_or_other_markers():
    import itertools
    s, r = result()
    fig = plot.root_map_figure(s, r.solutions, r, points=60)
    ax = fig.axes[0]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    numbers = [t for t in ax.texts if t.get_gid() == "spp_number"]
    assert len(numbers) == len(r.solutions)
    boxes = [t.get_window_extent(renderer) for t in numbers]
    assert not [(a.get_text(), b.get_text()) for (a, x), (b, y) in itertools.combinations(zip(numbers, boxes), 2)
                if x.overlaps(y)]
    centres = ax.transData.transform([(x.t1, x.t2) for x in r.solutions])
    for k, box in enumerate(boxes):
        others = [c for j, c in enumerate(centres) if j != k]
        assert not any(box.x0 < cx < box.x1 and box.y0 < cy < box.y1 for cx, cy in others), k
    frame = ax.get_window_extent(renderer)
    assert all(frame.x0 <= b.x0 and b.x1 <= frame.x1 and frame.y0 <= b.y0 and b.y1 <= frame.y1 for b in boxes)
    matplotlib.pyplot.close(fig)


# Issue 13 (attack): fig= a SubFigure failed in every figure function (tight_layout), though the docstrings offer it;
# a wrong kind of fig/ax gave AttributeErrors from inside matplotlib; spp_figure took axes= but not ax=.
def test_every_figure_function_fills_a_subfigure_and_refuses_wrong_kinds(tmp_path):
    import matplotlib.pyplot as plt
    s, r = result()
    sol = [x for x in r.solutions if x.admissible][0]
    m = spp.modes(spp.two_dof(), k=1, energy_max=2.0)
    root = plt.figure(figsize=(12, 8), layout="constrained")
    subs = root.subfigures(2, 3).ravel()
    draws = (lambda f: plot.spp_figure(s, sol, fig=f),
             lambda f: plot.frequency_energy_figure(r.solutions, fig=f),
             lambda f: plot.multipliers_figure(r.solutions, fig=f),
             lambda f: plot.modes_figure(m, r.solutions, fig=f),
             lambda f: plot.root_map_figure(s, r.solutions, (0, 3, 0, 3), points=40, fig=f,
                                            path=tmp_path / "all.png"))
    for sub, draw in zip(subs, draws):
        assert draw(sub) is sub and sub.axes
    assert (tmp_path / "all.png").stat().st_size > 0  # the root figure, saved
    for bad, match in ((dict(ax=3), "ax: expected matplotlib Axes"), (dict(ax=root), "got Figure"),
                       (dict(fig="x"), "fig: expected a matplotlib Figure or SubFigure")):
        with pytest.raises(TypeError, match=match):
            plot.frequency_energy_figure(r.solutions, **bad)
    with pytest.raises(TypeError, match="pair"):
        plot.spp_figure(s, sol, axes=3)
    from spp import animate
    with pytest.raises(TypeError, match="not a SubFigure"):
        animate.animation_of(s, sol, fig=subs[5])
    fig, axs = plt.subplots(1, 2)
    assert plot.spp_figure(s, sol, ax=axs[0]) is fig  # one cell split into the two panels (plus the force's twin)
    assert len(fig.axes) == 4 and axs[0] not in fig.axes and axs[1] in fig.axes
    with pytest.raises(ValueError, match="same argument"):
        plot.spp_figure(s, sol, ax=axs[1], axes=axs)
    plt.close("all")


# Issue 13: polar and 3-D Axes are Axes too: every figure function took them and drew nonsense (curves in t taken
# as angles, or on a z = 0 plane). Refused, naming the argument and the projection, before any work (the root map
# was sampled first).
def test_polar_and_3d_axes_are_refused_naming_the_argument(monkeypatch):
    import matplotlib.pyplot as plt
    s, r = result()
    sol = [x for x in r.solutions if x.admissible][0]
    m = spp.modes(spp.two_dof(), k=1, energy_max=2.0)
    monkeypatch.setattr(plot, "root_map", lambda *a, **k: pytest.fail("the root map was sampled"))
    fig = plt.figure()
    polar, three_d = fig.add_subplot(121, projection="polar"), fig.add_subplot(122, projection="3d")
    for bad, name in ((polar, "polar"), (three_d, "3d")):
        for draw, where in ((lambda a: plot.frequency_energy_figure(r.solutions, ax=a), "^ax: "),
                            (lambda a: plot.multipliers_figure(r.solutions, ax=a), "^ax: "),
                            (lambda a: plot.modes_figure(m, r.solutions, ax=a), "^ax: "),
                            (lambda a: plot.root_map_figure(s, r.solutions, r, ax=a), "^ax: "),
                            (lambda a: plot.spp_figure(s, sol, ax=a), "^spp_figure: ax: "),
                            (lambda a: plot.spp_figure(s, sol, axes=(a, fig.add_subplot(223))), "^spp_figure: axes: ")):
            with pytest.raises(TypeError, match=where + rf"expected rectilinear \(x-y\) matplotlib Axes .*got "
                                                        rf"\w+ of projection '{name}'"):
                draw(bad)
    plt.close("all")


# Issue 13 (attack): the root map's numbers were placed only on canvases that measure text (Agg); on a Figure()
# made without pyplot (and svg/pdf canvases) every number stayed up right of its marker and overlapped.
def test_root_map_numbers_are_placed_on_a_figure_without_an_agg_canvas():
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure
    s, r = result()
    bare, agg = Figure(), plt.figure()
    assert not hasattr(bare.canvas, "get_renderer")
    offsets = []
    for f in (bare, agg):
        plot.root_map_figure(s, r.solutions, r, points=60, fig=f)
        offsets.append([t.xyann for t in f.axes[0].texts if t.get_gid() == "spp_number"])
    assert offsets[0] == offsets[1] and len(set(offsets[0])) > 1
    plt.close("all")
