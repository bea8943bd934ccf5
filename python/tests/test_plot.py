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
