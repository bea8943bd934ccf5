"""Figures: files are valid images of the expected size, and the plotted data are the solver's."""
import os

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
    fig = plot.frequency_energy_figure(r, path=tmp_path / "fe.png")
    marked = {c.get_gid(): c.get_offsets() for c in fig.axes[0].collections}
    adm = np.array([(x.energy, 2 * np.pi / x.period) for x in r.solutions if x.admissible])
    assert np.allclose(np.sort(marked["admissible"], axis=0), np.sort(adm, axis=0))
    assert len(marked["potential"]) == 57
    assert mpimg.imread(tmp_path / "fe.png").shape[2] in (3, 4)
