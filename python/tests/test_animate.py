"""Animations: valid GIF/MP4 files with the expected frame count and size, the layout read from the system,
the frames drawn from the solver's orbit, clear errors and no file left behind on failure."""
import os
import shutil

import numpy as np
import pytest
from PIL import Image

import spp
from spp import animate

SRC = os.environ.get("SPP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def first_admissible(system, t1_max, t2_max):
    r = spp.solve(system, t1_max=t1_max, t2_max=t2_max, admissible_only=True)
    return r.solutions[0]


def test_layouts_follow_the_structure():
    assert animate.layout_of(spp.chain(5)) == "chain"
    assert animate.layout_of(spp.two_dof()) == "chain"
    assert animate.layout_of(spp.rod_with_slip()) == "plane"
    M = np.eye(3)
    K = np.array([[2.0, -1, -1], [-1, 2, -1], [-1, -1, 3]])  # springs between every pair: not a chain
    assert animate.layout_of(spp.System(M, K, np.array([0, 0, 1.0]), 1.0)) == "dofs"


@pytest.mark.parametrize("system,window,frames,dpi", [
    (spp.chain(5), (12, 12), 12, 80),
    (spp.rod_with_slip(), (8, 3), 9, 50),
])
def test_gif_has_the_frames_and_size_asked(tmp_path, system, window, frames, dpi):
    sol = first_admissible(system, *window)
    path = tmp_path / "a.gif"
    assert animate.animate(system, sol, path, frames=frames, periods=2, dpi=dpi) == 2 * frames
    with Image.open(path) as im:
        assert im.format == "GIF"
        assert im.size == (round(6.4 * dpi), round(4.8 * dpi))
        assert im.n_frames == 2 * frames
    assert [p.name for p in tmp_path.iterdir()] == ["a.gif"]  # no temporary file left


def test_frames_change_and_the_dofs_layout_works_for_any_system(tmp_path):
    system = spp.chain(5)
    sol = first_admissible(system, 12, 12)
    path = tmp_path / "d.gif"
    animate.animate(system, sol, path, frames=6, layout="dofs", dpi=40)
    with Image.open(path) as im:
        frames = []
        for k in range(im.n_frames):
            im.seek(k)
            frames.append(np.asarray(im.convert("L"), dtype=float))
    assert im.n_frames == 6
    assert max(np.abs(f - frames[0]).max() for f in frames[1:]) > 0  # the picture moves


@pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="ffmpeg not installed")
def test_mp4_with_ffmpeg(tmp_path):
    system = spp.chain(5)
    path = tmp_path / "a.mp4"
    animate.animate(system, first_admissible(system, 12, 12), path, frames=5, dpi=40)
    head = path.read_bytes()[:12]
    assert head[4:8] == b"ftyp"


def test_bad_arguments_are_refused_before_any_file(tmp_path):
    system = spp.chain(5)
    sol = first_admissible(system, 12, 12)
    for kwargs, words in ((dict(path=tmp_path / "a.png"), ".gif or .mp4"),
                          (dict(path=tmp_path / "a.gif", frames=1), "frames"),
                          (dict(path=tmp_path / "a.gif", layout="plane"), "two dofs"),
                          (dict(path=tmp_path / "a.gif", layout="nope"), "layout"),
                          # found by an independent review: dpi 100000 ended in matplotlib's IndexError, and
                          # 1e8 frames allocated 1.6 GB before a refusal
                          (dict(path=tmp_path / "a.gif", dpi=100000), r"dpi must be an integer in \[20, 600\]"),
                          (dict(path=tmp_path / "a.gif", frames=10 ** 8), r"frames must be an integer in \[2, 10000\]"),
                          (dict(path=tmp_path / "a.gif", frames=4000, periods=3), "frames x periods"),
                          (dict(path=tmp_path / "a.gif", frames=3000, dpi=200), "a GIF may hold in memory"),
                          (dict(path=tmp_path / "a.gif", fps=True), "fps")):
        with pytest.raises(ValueError, match=words):
            animate.animate(system, sol, **kwargs)
    assert list(tmp_path.iterdir()) == []


# Found by an independent attack on issue 13: an inadmissible SPP was animated from the simulator (which leaves the
# orbit at the first impact), on [0, T] instead of the static figure's [-2 t1, 2 t2], gap and force on one axis.
def test_inadmissible_spp_is_animated_as_its_potential_orbit_on_the_figures_time_axis(tmp_path):
    s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
    r = spp.solve(s, t1_max=12, t2_max=12)
    sol = next(x for x in r.solutions if not x.admissible and x.min_gap < 0)
    fig, update, count = animate._figure(s, sol, frames=10, periods=1, kind="chain")
    try:
        gap_ax, force_ax = [a for a in fig.axes if any(l.get_gid() == "gap" for l in a.lines)][0], \
            [a for a in fig.axes if any(l.get_gid() == "force" for l in a.lines)][0]
        assert gap_ax is not force_ax  # twin axes, each with its label
        assert "gap" in gap_ax.get_ylabel() and "force" in force_ax.get_ylabel()
        t, gap = [l for l in gap_ax.lines if l.get_gid() == "gap"][0].get_data()
        ref = spp.trajectory(s, sol.t1, sol.t2, 2000)
        assert np.isclose(gap.min(), ref["gap"].min(), rtol=1e-3, atol=1e-9)  # the potential orbit, gap < 0
        assert gap.min() < 0
        step = sol.period / 1000  # (2000 samples a period: the ends within a sample)
        assert abs(t.min() + 2 * sol.t1) < step and abs(t.max() - 2 * sol.t2) < step
        assert gap_ax.get_xlim() == pytest.approx((-2 * sol.t1, 2 * sol.t2))
        assert any(c.get_gid() == "violation" for c in gap_ax.collections)
        assert "NOT ADMISSIBLE" in fig._suptitle.get_text()
        update(count - 1)
    finally:
        import matplotlib.pyplot as plt
        plt.close(fig)
    animate.animate(s, sol, tmp_path / "i.gif", frames=4, dpi=40)


# Issue 13: each frame showed the sample nearest its time (2000 a period: off by up to half a sample, ~1e-3 of the
# motion); the frames are now the exact states at their times (spp.trajectory(times=...), the SPP's own flows), at
# any fps. A frame between samples matches the exact simulator started at the SPP's onset state.
@pytest.mark.parametrize("g0_zero", [False, True])
def test_frames_are_the_exact_states_at_their_times(g0_zero):
    import matplotlib.pyplot as plt
    if g0_zero:  # a zero-gap SPP (paper 6.1): drawn from the simulator (trajectory cannot re-solve it)
        ps = spp.ParametricSystem.from_json(os.path.join(SRC, "examples", "two_dof_zero_gap.json"))
        closure = spp.continue_branches(ps, t1_max=3, t2_max=1).gap_closures()[0]
        s, sol = ps.at(closure.mu), closure
    else:
        s = spp.System.from_json(os.path.join(SRC, "examples", "chain5.json"))
        sol = first_admissible(s, 12, 12)
    frames = 7
    fig, update, count = animate._figure(s, sol, frames=frames, periods=1, kind="dofs")
    try:
        T = sol.period
        for k in (1, 3, 6):
            artists = update(k)
            cursor, tops = artists[0], artists[-1]
            time = -2 * sol.t1 + k * T / frames
            assert cursor.get_xdata()[0] == pytest.approx(time, abs=1e-12)
            ref = spp.simulate(s, sol.x0, sol.v0, T, 0.0, sample_times=[np.mod(time, T)], sample_events=False)
            exact = ref.x[np.searchsorted(ref.t, np.mod(time, T))]
            shown = np.asarray(tops.get_ydata(), dtype=float)
            assert np.abs(shown - exact).max() <= 1e-10 * max(np.abs(exact).max(), 1.0), (k, shown - exact)
    finally:
        plt.close(fig)
    if not g0_zero:  # trajectory(times=): the uniform samples at their times, any time modulo the period
        tr = spp.trajectory(s, sol.t1, sol.t2, 11)
        at = spp.trajectory(s, sol.t1, sol.t2, times=np.r_[tr["t"][3], tr["t"][3] + 2 * tr["period"], -tr["t"][7]])
        assert np.allclose(at["x"][0], tr["x"][3], rtol=0, atol=1e-12) and np.allclose(at["x"][1], tr["x"][3], atol=1e-9)
        assert np.allclose(at["x"][2], tr["x"][3], rtol=0, atol=1e-9)  # -7 T / 10 is 3 T / 10, a period on
        assert list(at["t"]) == [tr["t"][3], tr["t"][3] + 2 * tr["period"], -tr["t"][7]]
        with pytest.raises(ValueError, match="trajectory: times must be a non-empty vector of finite numbers"):
            spp.trajectory(s, sol.t1, sol.t2, times=[np.nan])


# Found by the same attack: the docs' GIFs were 384 x 288 (dpi 60), their text unreadable.
def test_docs_gifs_are_web_sized_and_small():
    for name in ("chain5_spp1.gif", "rod4_spp.gif"):
        path = os.path.join(SRC, "docs", "img", name)
        with Image.open(path) as im:
            assert im.size[0] >= 800, (name, im.size)
        assert os.path.getsize(path) < 2 * 1024 ** 2, name


# Found by an independent attack on issue 13: the default frames were 512 x 384 (dpi 80), the legend's text ~4 px
# high; and past 12 dofs the positions' axis had ticks at 2.5, 7.5 (no dof has such an index).
def test_default_frames_are_800_by_600_and_dof_ticks_are_whole(tmp_path):
    import inspect
    import matplotlib.pyplot as plt
    assert inspect.signature(animate.animate).parameters["dpi"].default == 125
    assert (round(6.4 * animate.DEFAULT_DPI), round(4.8 * animate.DEFAULT_DPI)) == (800, 600)
    fig, ax = plt.subplots()
    animate._Dofs(ax, np.linspace(-1, 1, 40).reshape(2, 20))
    fig.canvas.draw()
    ticks = [t for t in ax.get_xticks() if 0.3 <= t <= 20.7]
    assert ticks and all(float(t).is_integer() for t in ticks), ticks
    plt.close(fig)


# Issue 13: an animation could only be written to a file; in Jupyter it is shown inline from animation_html
# (matplotlib's to_jshtml, frames embedded), drawn into a given figure when fig= is passed, as animate() now takes.
def test_animation_shows_inline_and_draws_into_a_given_figure(tmp_path):
    import matplotlib.pyplot as plt
    system = spp.chain(5)
    sol = first_admissible(system, 12, 12)
    before = set(plt.get_fignums())
    html = animate.animation_html(system, sol, frames=6)
    assert html._repr_html_() == html and "<script" in html and html.count("data:image/png;base64") == 6
    assert set(plt.get_fignums()) == before  # its own figure closed: the cell shows the animation only
    # its text/plain form (stored by Jupyter beside the HTML) is one short line, not the HTML again
    import IPython.lib.pretty as pretty
    for text in (repr(html), pretty.pretty(html)):
        assert text.startswith("<AnimationHTML:") and len(text) < 100
    anim = animate.animation_of(system, sol, frames=5, periods=2)
    assert anim.to_jshtml().count("data:image/png;base64") == 10
    plt.close(anim._fig)
    fig = plt.figure(figsize=(5, 4), dpi=40)
    assert animate.animate(system, sol, tmp_path / "a.gif", frames=4, dpi=40, fig=fig) == 4
    with Image.open(tmp_path / "a.gif") as im:
        assert im.size == (200, 160) and im.n_frames == 4
    assert plt.fignum_exists(fig.number) and len(fig.axes) >= 3  # the caller's figure, drawn into, kept open
    with pytest.raises(ValueError, match="frames must be an integer"):
        animate.animation_html(system, sol, frames=1)
    plt.close("all")


# Issue 13: a finite-element model was drawn as a stem plot of its dofs (or, reduced, of its modal coordinates).
# `spp generate bar` writes the model's layout (node coordinates, dof directions), `spp reduce --layout` carries it
# to the reduced model with the rows of the reduction basis, and layout "fe" draws the model itself.
def test_fe_layout_draws_the_model_from_the_reduction_basis(tmp_path):
    import json
    import subprocess
    cli = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(spp.__file__)))), "spp")
    run = lambda *a: subprocess.run([cli, *a], check=True, capture_output=True, text=True, cwd=tmp_path)
    run("generate", "bar", "--n", "200", "--out", "bar.json")
    out = run("reduce", "bar.json", "--modes", "3", "--out", "r.json", "--layout", "bar.layout.json").stdout
    assert "wrote r.layout.json (200 dofs" in out
    layout = json.loads((tmp_path / "r.layout.json").read_text())
    assert len(layout["dofs"]) == 200 and np.shape(layout["basis"]) == (200, 4)
    system = spp.System.from_json(str(tmp_path / "r.json"))
    # the free end (dof 199) is the contact dof: its basis row is u = q_0 (the reduced model's first coordinate)
    assert layout["basis"][199] == [1.0, 0.0, 0.0, 0.0]
    sol = spp.nearest_spp(system, 1.0894, 0.4628).solution  # the bar's first admissible SPP (m = 3)
    anim = animate.animation_of(system, sol, frames=8, fe_layout=tmp_path / "r.layout.json")
    fig = anim._fig
    line = [l for ax in fig.axes for l in ax.lines if l.get_gid() == "fe_displacement"][0]
    obstacle = [l for ax in fig.axes for l in ax.lines if l.get_gid() == "obstacle"][0]
    anim._func(3)
    t = -2 * sol.t1 + 3 * sol.period / 8
    x = spp.trajectory(system, sol.t1, sol.t2, 4000)  # the reduced state at that instant, expanded by the basis
    tt = np.where(x["t"] > 2 * sol.t2, x["t"] - sol.period, x["t"])
    k = np.argmin(np.abs(tt - t))
    expected = np.asarray(layout["basis"]) @ x["x"][k]
    assert np.allclose(line.get_ydata(), expected, atol=2e-3 * np.abs(expected).max())
    assert np.allclose(line.get_xdata(), np.arange(1, 201) / 200)
    # the obstacle at the free end, where the gap closes: g = g0 - x_tip = 0
    assert np.allclose(obstacle.get_ydata(), [system.g0 / -system.w[0]] * 2)
    import matplotlib.pyplot as plt
    plt.close(fig)
    # a layout of another model, or the wrong layout kind, is refused naming why
    with pytest.raises(ValueError, match=r"r.layout.json is not a layout of the system given: field \"basis\": "
                                         r"expected rows of 5 numbers .*got 4: the layout of another reduced model"):
        animate.animation_of(spp.chain(5), spp.solve(spp.chain(5), t1_max=12, t2_max=12).solutions[0],
                             fe_layout=tmp_path / "r.layout.json")
    with pytest.raises(ValueError, match="layout 'fe' needs fe_layout"):
        animate.animation_of(system, sol, layout="fe")
    with pytest.raises(ValueError, match="unknown field"):
        animate.FeLayout.read({"dofs": [0], "coordinates": [[0]], "directions": [[1]], "nodes": 1}, spp.chain(4))


# Issue 13: a layout of another reduced model with as many dofs (m) was caught by nothing (only the basis' shape was
# checked): drawn over the wrong model. spp reduce --layout writes the reduced model's fingerprint (m and weighted
# sums of M, K, w, and g0: they survive the files' round trips) into its layout; where it is drawn (Python fe_layout=,
# spp animate --fe-layout), a layout whose fingerprint is another model's is refused naming both.
def test_a_layout_of_another_reduced_model_with_as_many_dofs_is_refused_naming_both(tmp_path):
    import json
    import subprocess
    cli = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(spp.__file__)))), "spp")
    run = lambda *a, check=True: subprocess.run([cli, *a], check=check, capture_output=True, text=True, cwd=tmp_path)
    for n, stem in ((200, "a"), (120, "b")):  # two bars, each reduced to m = 3: bases of one shape
        run("generate", "bar", "--n", str(n), "--out", f"{stem}.json")
        run("reduce", f"{stem}.json", "--modes", "3", "--out", f"r{stem}.json", "--layout", f"{stem}.layout.json")
    fa = json.loads((tmp_path / "ra.layout.json").read_text())["model_fingerprint"]
    assert len(fa) == 5 and fa[0] == 4
    sa, sb = spp.System.from_json(str(tmp_path / "ra.json")), spp.System.from_json(str(tmp_path / "rb.json"))
    assert animate.FeLayout.read(tmp_path / "ra.layout.json", sa).fingerprint[0] == 4  # its own model: taken
    with pytest.raises(ValueError, match=r"rb.layout.json is not a layout of the system given: field "
                                         r"\"model_fingerprint\": expected the fingerprint of this reduced model"):
        animate.FeLayout.read(tmp_path / "rb.layout.json", sa)
    sol = spp.solve(sa, t1_max=2.5, t2_max=2.5, admissible_only=True).solutions[0]
    with pytest.raises(ValueError, match="model_fingerprint"):  # also a FeLayout read before, for another system
        animate.animation_of(sa, sol, frames=4, fe_layout=animate.FeLayout.read(tmp_path / "rb.layout.json", sb))
    # the command line, through a result file (the system read back from it): both files named
    run("solve", "ra.json", "--t1-max", "2.5", "--t2-max", "2.5", "--admissible-only", "--json", "sa.json")
    ok = run("animate", "sa.json", "--fe-layout", "ra.layout.json", "--frames", "3", "--dpi", "30", "--out", "a.gif")
    assert "layout fe" in ok.stdout
    bad = run("animate", "sa.json", "--fe-layout", "rb.layout.json", "--frames", "3", "--dpi", "30", "--out", "b.gif",
              check=False)
    assert bad.returncode != 0 and not (tmp_path / "b.gif").exists()
    assert "rb.layout.json is not a layout of sa.json" in bad.stderr and "model_fingerprint" in bad.stderr, bad.stderr


def test_fe_layout_in_two_dimensions_moves_each_node_by_its_dofs():
    # a hand-written layout of chain5: dofs 0, 1 move node (0, 0) along x and y; dofs 2..4 three nodes along y
    system = spp.chain(5)
    sol = first_admissible(system, 12, 12)
    layout = {"dofs": [0, 1, 2, 3, 4], "coordinates": [[0, 0], [0, 0], [1, 0], [2, 0], [3, 0]],
              "directions": [[1, 0], [0, 2], [0, 1], [0, 1], [0, 1]]}
    anim = animate.animation_of(system, sol, frames=5, fe_layout=layout)
    anim._func(2)
    cloud = [l for ax in anim._fig.axes for l in ax.lines if l.get_gid() == "fe_displacement"][0]
    scene_nodes = np.column_stack(cloud.get_data())
    assert scene_nodes.shape == (4, 2)  # four nodes: the first carries two dofs
    import matplotlib.pyplot as plt
    plt.close(anim._fig)


# Found by an attack on issue 13: a plate in x-y whose dofs move along z was drawn motionless (the first two axes,
# "displacements x 1e+299"); duplicate or non-integer dofs passed the Python reader; a layout of another full model
# passed spp reduce; spp_figure(ax=) on an add_axes Axes raised an AttributeError.
def test_fe_layout_out_of_plane_motion_and_loose_input():
    system = spp.chain(5)
    sol = first_admissible(system, 12, 12)
    layout = {"dofs": [0, 1, 2, 3, 4], "coordinates": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0]],
              "directions": [[0, 0, 1]] * 5}
    anim = animate.animation_of(system, sol, frames=5, fe_layout=layout)
    ax = [a for a in anim._fig.axes if a.get_xlabel() == "x (-)"][0]
    assert ax.get_ylabel() == "z (-)"
    anim._func(2)
    cloud = [l for l in ax.lines if l.get_gid() == "fe_displacement"][0]
    y = np.asarray(cloud.get_ydata())
    assert len(y) == 5 and np.ptp(y) > 0  # five nodes (two pairs share x: not merged), moving
    import matplotlib.pyplot as plt
    plt.close(anim._fig)
    base = {"coordinates": [[0], [1]], "directions": [[1], [1]]}
    for dofs, match in (([0, 0], "each dof once"), (["0", 1], r'fe_layout: field "dofs"\[0\] must be a number'),
                        ([True, 1], r'fe_layout: field "dofs"\[0\] must be a number'),
                        ([0.5, 1], r'fe_layout: field "dofs"\[0\]: expected a whole number from 0 up')):
        with pytest.raises(ValueError, match=match):
            animate.FeLayout.read(dict(base, dofs=dofs), spp.chain(5))
    assert animate.FeLayout.read(dict(base, dofs=[0, 1], directions=[[1e-300], [1]]),
                                 spp.chain(5)).dofs.tolist() == [0, 1]
    from spp import plot
    fig = plt.figure()
    with pytest.raises(ValueError, match="placed by add_axes"):
        plot.spp_figure(system, sol, ax=fig.add_axes([0.1, 0.1, 0.8, 0.8]))
    a = fig.add_subplot(2, 1, 1)
    with pytest.raises(ValueError, match="the same Axes twice"):
        plot.spp_figure(system, sol, ax=(a, a))
    plt.close("all")
