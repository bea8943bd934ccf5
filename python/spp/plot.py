"""Figures like the paper's (matplotlib, Agg): an SPP over one period (Figs. 5 and 7) and the frequency-energy
plot of the SPPs found. Each function returns the matplotlib Figure and, given a path, saves it (the suffix
picks PNG, SVG or PDF)."""
import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ._spp import simulate  # noqa: E402

COLUMN_WIDTH_IN = 3.5  # one journal column


def _save(fig, path, dpi=200):
    if path is not None:
        fig.savefig(path, dpi=dpi, bbox_inches="tight")
    return fig


def spp_figure(system, solution, samples=2000, path=None):
    """Top: gap and normal contact force over one period, contact phase shaded, symmetry axes at -t1 (mid-flight)
    and t2 (mid-contact); bottom: every position. Time origin at contact onset: flight on [-2 t1, 0], contact on
    [0, 2 t2]. The curves come from spp.simulate (exact flows) started at the solution's x0, v0."""
    T, t1, t2 = solution.period, solution.t1, solution.t2
    sim = simulate(system, solution.x0, solution.v0, T, 0.0, samples / T)
    t = np.where(sim.t > 2 * t2, sim.t - T, sim.t)  # flight after the contact is the flight before it
    order = np.argsort(t, kind="stable")
    t, x, gap, force = t[order], sim.x[order], sim.gap[order], sim.force[order]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(COLUMN_WIDTH_IN * 2, 4.6),
                                      gridspec_kw={"height_ratios": [1, 1.3]})
    for ax in (top, bottom):
        ax.axvspan(0.0, 2 * t2, color="0.88", lw=0, label="contact phase" if ax is top else None)
        ax.axvline(-t1, color="0.4", ls=":", lw=1)
        ax.axvline(t2, color="0.4", ls=":", lw=1)
    top.plot(t, gap, color="C0", lw=1.4, label="gap $g$ (-)")
    top.plot(t, force, color="C3", lw=1.4, label=r"contact force $\lambda$ (-)")
    top.axhline(0.0, color="k", lw=0.6)
    top.set_ylabel("gap, force (-)")
    top.legend(loc="best", fontsize=8, frameon=False)
    state = "admissible" if solution.admissible else "not admissible"
    top.set_title(f"SPP $t_1$ = {t1:.6g}, $t_2$ = {t2:.6g}, $T$ = {T:.6g} ({state})", fontsize=9, pad=14)
    for i in range(x.shape[1]):
        bottom.plot(t, x[:, i], lw=1.1, label=f"$x_{{{i + 1}}}$")
    bottom.set_xlabel("time $t$ (-)")
    bottom.set_ylabel("positions (-)")
    bottom.legend(loc="best", fontsize=7, ncol=min(5, x.shape[1]), frameon=False)
    bottom.set_xlim(-2 * t1, 2 * t2)
    for ax, tick, name in ((top, -t1, "$-t_1$"), (top, t2, "$t_2$")):
        ax.annotate(name, (tick, 1.0), xycoords=("data", "axes fraction"), ha="center", va="bottom", fontsize=8)
    fig.tight_layout()
    return _save(fig, path)


def frequency_energy_figure(result, path=None):
    """Frequency 2 pi / T against energy of every SPP of a solve() result; admissible ones filled."""
    sols = list(result.solutions)
    fig, ax = plt.subplots(figsize=(COLUMN_WIDTH_IN, 2.8))
    for admissible, style in ((False, dict(facecolors="none", edgecolors="0.5", label="potential SPP")),
                              (True, dict(color="C3", label="admissible SPP"))):
        pts = [(s.energy, 2 * np.pi / s.period) for s in sols if s.admissible == admissible]
        if pts:
            e, f = np.array(pts).T
            ax.scatter(e, f, s=14, lw=0.8, gid="admissible" if admissible else "potential", **style)
    ax.set_xscale("log")
    ax.set_xlabel("energy $E$ (-)")
    ax.set_ylabel(r"frequency $2\pi/T$ (-)")
    ax.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    return _save(fig, path)
