"""Figures like the paper's: the root map of a window (Fig. 4), an SPP over one period (Figs. 5 and 7) and the
frequency-energy plot of the SPPs found. Each function draws into the axes it is given (ax=, or axes= for the two
panels of spp_figure), into the figure it is given (fig=, cleared first: its size is the caller's) or into a new
figure, returns the Figure and, given a path, saves it (the suffix picks PNG, SVG or PDF). Animations: spp.animate
(animation_html shows one inline in Jupyter). Importing this module leaves matplotlib's backend alone, so figures
show inline in Jupyter and with plt.show(); `python3 -m spp plot` (headless) selects Agg itself."""
import warnings
import numpy as np

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from ._files import atomic_path
from ._spp import root_map, simulate, trajectory

COLUMN_WIDTH_IN = 3.5  # one journal column


def save_atomic(fig, path, dpi=200):
    """Saves to a temporary file beside path, then renames it over path: never a half-written figure."""
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, bbox_inches="tight")


def _window(window):
    """A window as a dict t1_min, t1_max, t2_min, t2_max, from such a dict, a SolveResult (its window) or a tuple
    (t1_min, t1_max, t2_min, t2_max)."""
    keys = ("t1_min", "t1_max", "t2_min", "t2_max")
    if isinstance(window, dict):
        missing = [k for k in keys if k not in window]
        if missing:
            raise ValueError(f"window: missing {', '.join(missing)} (expected a dict with {', '.join(keys)})")
        return window
    if all(hasattr(window, k) for k in keys):
        return {k: getattr(window, k) for k in keys}
    try:
        values = [float(v) for v in window]
    except TypeError:
        values = []
    if len(values) != 4:
        raise ValueError(f"window: expected a dict with {', '.join(keys)}, a SolveResult or a 4-tuple in that order, "
                         f"got {window!r}")
    return dict(zip(keys, values))


def _checked(ax=None, fig=None, where="ax"):
    """ax and fig as given, refused with a TypeError naming what they are when they are not matplotlib Axes and a
    Figure or SubFigure (a wrong kind gave AttributeErrors from deep inside matplotlib; found by an attack)."""
    from matplotlib.axes import Axes
    from matplotlib.figure import FigureBase
    if ax is not None and not isinstance(ax, Axes):
        raise TypeError(f"{where}: expected matplotlib Axes (e.g. plt.subplots()[1]), got {type(ax).__name__}")
    # polar and 3-D Axes (and the map projections) are Axes too, and took the curves as angles or on a z = 0 plane:
    # nonsense drawn silently (issue 13)
    if ax is not None and ax.name != "rectilinear":
        raise TypeError(f"{where}: expected rectilinear (x-y) matplotlib Axes (e.g. plt.subplots()[1]), got "
                        f"{type(ax).__name__} of projection {ax.name!r}")
    if fig is not None and not isinstance(fig, FigureBase):
        raise TypeError(f"fig: expected a matplotlib Figure or SubFigure (plt.figure(), fig.subfigures()), got "
                        f"{type(fig).__name__}")
    return ax, fig


def _lay_out(fig):
    """Lays out a figure this call made or filled: tight_layout on a Figure without a layout engine of its own; a
    SubFigure is laid out with its root figure (make that one with layout="constrained"), as are figures with an
    engine (tight_layout failed on every SubFigure given as fig=; found by an attack)."""
    from matplotlib.figure import Figure
    if isinstance(fig, Figure) and fig.get_layout_engine() is None:
        fig.tight_layout()


def _axes(ax, figsize, fig=None):
    """The axes to draw into, their figure, and whether the figure is this call's own (then laid out here): ax when
    given; else one axes filling fig (a Figure or SubFigure, e.g. plt.figure(figsize=...), cleared first); else a new
    figure."""
    _checked(ax, fig)
    if ax is not None:
        if fig is not None and ax.figure is not fig:
            raise ValueError("ax and fig: expected ax in fig (or only one of them), got axes of another figure")
        return ax.figure, ax, False
    if fig is not None:
        fig.clf()
        return fig, fig.add_subplot(), True
    fig, ax = plt.subplots(figsize=figsize)
    return fig, ax, True


def _save(fig, path, dpi=200):
    if path is not None:
        save_atomic(fig.figure, path, dpi)  # a SubFigure's root figure (Figure.figure is itself)
    return fig


def _align_zeros(left, right):
    """Sets both y ranges so that their zeros are at the same height (gap and force share the zero line)."""
    (a0, a1), (b0, b1) = left.get_ylim(), right.get_ylim()
    # fraction of the height below zero, the larger of the two, applied to both
    f = max(-a0 / (a1 - a0) if a0 < 0 else 0.0, -b0 / (b1 - b0) if b0 < 0 else 0.0)
    f = min(max(f, 0.05), 0.9)  # a margin under a curve that touches zero
    for ax, lo, hi in ((left, a0, a1), (right, b0, b1)):
        top = max(hi, 0.0)
        bottom = max(-lo, 0.0)
        top = max(top, bottom * (1 - f) / f) if f > 0 else top
        ax.set_ylim(-f * top / (1 - f), top)


def _dof_colors(n):
    """Matplotlib's cycle up to 10 dofs; past it, a sequential colour map (dof 1 to n), which does not repeat."""
    if n <= 10:
        return [f"C{i}" for i in range(n)]
    return [plt.get_cmap("viridis")(i / (n - 1)) for i in range(n)]


def _one_period(system, solution, samples):
    """t (from contact onset), x, gap, force over one period: from the SPP's own equations (spp.trajectory), or, for a
    zero-gap SPP of paper §6.1 (g0 = 0: it exists only at one parameter value, where trajectory cannot re-solve it),
    from the exact simulator started at its onset state x0, v0 (it has one, as a BranchPoint or Solution). Ctrl-C:
    KeyboardInterrupt, no figure of part of a period (trajectory and simulate return what they computed)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the interrupted run's warning: raised below instead
        if system.g0 != 0.0:
            tr = trajectory(system, solution.t1, solution.t2, samples)
            if tr["interrupted"]:
                raise KeyboardInterrupt(f"trajectory interrupted: {len(tr['t'])} of {samples} samples")
            return tr
        sim = simulate(system, solution.x0, solution.v0, solution.period, 0.0, samples / solution.period)
    if sim.status == "interrupted":
        raise KeyboardInterrupt("simulation interrupted")
    return {"t": sim.t, "x": sim.x, "gap": sim.gap, "force": sim.force}


def spp_figure(system, solution, samples=2000, path=None, axes=None, fig=None, ax=None):
    """Top: gap (left axis) and normal contact force (right axis, its own scale) over one period, contact phase
    shaded, symmetry axes at -t1 (mid-flight) and t2 (mid-contact); bottom: every position (coloured by dof index
    past 10 dofs, with a colour bar instead of a legend). Time origin at contact onset: flight on [-2 t1, 0], contact
    on [0, 2 t2]. The curves come from spp.trajectory (the SPP's own equations, exact flows), so an inadmissible
    SPP is drawn as the potential orbit it is (gap or force negative somewhere, marked), as spp trajectory writes it;
    a zero-gap SPP (g0 = 0, paper §6.1, e.g. a gap closure of continue_branches) from the exact simulator.
    axes (or ax, the same): (top, bottom) to draw into, or one Axes whose place (its subplot cell) the two panels
    take (it is removed); fig: a Figure to draw both panels into (cleared first, e.g. plt.figure(figsize=(8, 5)) or
    a subfigure, laid out by its root figure); default a new figure. Returns the figure (a SubFigure when given
    one)."""
    T, t1, t2 = solution.period, solution.t1, solution.t2
    tr = _one_period(system, solution, samples)
    t = np.where(tr["t"] > 2 * t2, tr["t"] - T, tr["t"])  # flight after the contact is the flight before it
    order = np.argsort(t, kind="stable")
    t, x, gap, force = t[order], tr["x"][order], tr["gap"][order], tr["force"][order]
    if ax is not None and axes is not None:
        raise ValueError("spp_figure: ax and axes are the same argument: expected one of them, got both")
    axes = _two_panels(ax if axes is None else axes, fig)
    own = axes is None
    if axes is not None:
        top, bottom = axes
        if fig is not None and top.figure is not fig:
            raise ValueError("axes and fig: expected axes in fig (or only one of them), got axes of another figure")
        fig = top.figure
    elif fig is not None:
        fig.clf()
        top, bottom = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [1, 1.3]})
    else:
        fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(COLUMN_WIDTH_IN * 2, 4.6),
                                          gridspec_kw={"height_ratios": [1, 1.3]})
    for ax in (top, bottom):
        ax.axvspan(0.0, 2 * t2, color="0.88", lw=0, label="contact phase" if ax is top else None)
        ax.axvline(-t1, color="0.4", ls=":", lw=1)
        ax.axvline(t2, color="0.4", ls=":", lw=1)
    top.plot(t, gap, color="C0", lw=1.4, label="gap $g$ (-)")
    top.axhline(0.0, color="k", lw=0.6)
    top.set_ylabel("gap $g$ (-)", color="C0")
    right = top.twinx()  # the force has its own scale (at n = 20 the gap reaches 500 and the force 40)
    right.plot(t, force, color="C3", lw=1.4, label=r"contact force $\lambda$ (-)")
    right.set_ylabel(r"contact force $\lambda$ (-)", color="C3")
    # a potential SPP's violations of ineqs. (5.3): gap < 0 in flight, force < 0 in contact, shaded in red
    flight, contact = t < 0, (t >= 0) & (t <= 2 * t2)
    scale_g, scale_f = max(np.abs(gap).max(), 1e-300), max(np.abs(force).max(), 1e-300)
    bad_gap, bad_force = flight & (gap < -1e-9 * scale_g), contact & (force < -1e-9 * scale_f)
    if bad_gap.any():
        top.fill_between(t, gap, 0.0, where=bad_gap, color="red", alpha=0.35, lw=0, label="gap < 0 in flight")
    if bad_force.any():
        right.fill_between(t, force, 0.0, where=bad_force, color="red", alpha=0.2, lw=0, hatch="//",
                           label="force < 0 in contact")
    _align_zeros(top, right)
    handles = top.get_legend_handles_labels()[0] + right.get_legend_handles_labels()[0]
    # outside the axes, right of the force's axis label: it covered the flight's curves (found by an attack)
    top.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.2, 1.0), fontsize=7, frameon=False)
    state = "admissible" if solution.admissible else "not admissible"
    top.set_title(f"SPP $t_1$ = {t1:.6g}, $t_2$ = {t2:.6g}, $T$ = {T:.6g} ({state})", fontsize=9, pad=14)
    n = x.shape[1]
    for i, color in enumerate(_dof_colors(n)):
        bottom.plot(t, x[:, i], lw=1.1 if n <= 10 else 0.8, color=color, label=f"$x_{{{i + 1}}}$")
    bottom.set_xlabel("time $t$ (-)")
    bottom.set_ylabel("positions (-)")
    if n <= 10:
        bottom.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
    bottom.set_xlim(-2 * t1, 2 * t2)
    for ax, tick, name in ((top, -t1, "$-t_1$"), (top, t2, "$t_2$")):
        ax.annotate(name, (tick, 1.0), xycoords=("data", "axes fraction"), ha="center", va="bottom", fontsize=8)
    if own:
        _lay_out(fig)
    if n > 10:  # after the layout, under the positions (their width, so the time axes stay aligned)
        sm = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(1, n))
        fig.colorbar(sm, ax=bottom, orientation="horizontal", location="bottom", label="dof index", pad=0.3,
                     fraction=0.06, aspect=40)
    return _save(fig, path)


def _two_panels(axes, fig):
    """spp_figure's (top, bottom) axes from what was given: None; a pair of Axes; or one Axes made by add_subplot or
    subplots, whose cell is split into the two panels (the Axes is removed)."""
    from matplotlib.axes import Axes
    _checked(fig=fig)
    if axes is None:
        return None
    if isinstance(axes, Axes):
        _checked(axes, where="spp_figure: ax")
        spec = getattr(axes, "get_subplotspec", lambda: None)()  # (add_axes and inset axes have none)
        if spec is None:
            raise ValueError("spp_figure: ax: expected a pair (top, bottom) of Axes or one Axes of a subplot grid "
                             "(add_subplot, subplots), got an Axes placed by add_axes")
        parent = axes.figure
        if fig is not None and parent is not fig:
            raise ValueError("ax and fig: expected ax in fig (or only one of them), got axes of another figure")
        axes.remove()
        grid = spec.subgridspec(2, 1, height_ratios=[1, 1.3], hspace=0.1)
        top = parent.add_subplot(grid[0])
        return top, parent.add_subplot(grid[1], sharex=top)
    try:
        pair = tuple(axes)
    except TypeError:
        pair = ()
    if len(pair) != 2:
        raise TypeError(f"spp_figure: axes: expected a pair (top, bottom) of Axes or one Axes, got "
                        f"{type(axes).__name__}")
    for a in pair:
        _checked(a, where="spp_figure: axes")
    if pair[0] is pair[1] or pair[0].figure is not pair[1].figure:
        raise ValueError("spp_figure: axes: expected two different Axes of one figure (top, bottom), got "
                         + ("the same Axes twice" if pair[0] is pair[1] else "Axes of two figures"))
    return pair


def _scatter_spps(ax, solutions, x, y):
    """Potential SPPs as open circles (gid "potential"), admissible ones filled (gid "admissible")."""
    for admissible, style in ((False, dict(facecolors="none", edgecolors="0.35", label="potential SPP")),
                              (True, dict(color="C3", label="admissible SPP"))):
        pts = [(x(s), y(s)) for s in solutions if s.admissible == admissible]
        if pts:
            a, b = np.array(pts).T
            ax.scatter(a, b, s=16, lw=0.8, zorder=3, gid="admissible" if admissible else "potential", **style)


def _frequency_energy_spps(ax, sols, stable_label):
    """SPPs on frequency-energy axes (log energy): _scatter_spps' markers plus, when the solutions carry their
    stability (Solution, docs/stability.md), a black ring around each transversally stable one (gid "stable")."""
    _scatter_spps(ax, sols, lambda s: s.energy, lambda s: 2 * np.pi / s.period)
    stable = [(s.energy, 2 * np.pi / s.period) for s in sols if getattr(s, "stable", False)]
    if stable:
        a, b = np.array(stable).T
        ax.scatter(a, b, s=70, facecolors="none", edgecolors="k", lw=1.0, zorder=4, gid="stable", label=stable_label)
    ax.set_xscale("log")
    ax.set_xlabel("energy $E$ (-)")
    ax.set_ylabel(r"frequency $2\pi/T$ (-)")


def _merged_cells(rm):
    """The root map's cells as one grid (t1, t2, symmetric, onset) for a single contour call per condition: the
    cells tile the window as a tensor product (rows of equal t2 grids, columns of equal t1 grids), so their grids are
    concatenated, with one masked (NaN) row or column on each pole line between two cells so that no contour joins
    the two sides of a pole (where the sampled functions change sign through infinity)."""
    cells = list(rm.cells)
    ncols = 1
    while ncols < len(cells) and np.array_equal(cells[ncols].t2, cells[0].t2):
        ncols += 1
    nrows = len(cells) // ncols
    grid = [cells[r * ncols:(r + 1) * ncols] for r in range(nrows)]

    def axis(parts):  # grids of consecutive cells, a separator between them (strictly increasing)
        out, keep = [], []
        for k, part in enumerate(parts):
            if k:
                out.append([0.5 * (out[-1][-1] + part[0])])
                keep.append(False)
            out.append(np.asarray(part, dtype=float))
            keep.extend([True] * len(part))
        return np.concatenate(out), np.array(keep)

    t1, keep1 = axis([c.t1 for c in grid[0]])
    t2, keep2 = axis([row[0].t2 for row in grid])
    merged = []
    for field in ("symmetric", "onset"):
        blocks = [np.hstack([getattr(c, field) for c in row]) for row in grid]
        values = np.full((len(t2), len(t1)), np.nan)
        values[np.ix_(keep2, keep1)] = np.vstack(blocks)
        merged.append(values)
    return t1, t2, merged[0], merged[1]


# The uncertified regions of a result (SolveResult.uncertified) on the root map: one style per cause, the cause in the
# legend. "interrupted" (cells a stopped search never reached) is the one that can cover much of the window.
# Drawn over the curves (below the SPP markers), translucent: a region is seen whatever is drawn under it.
UNCERTIFIED_STYLES = {
    "interrupted": dict(facecolor="0.45", alpha=0.55, label="not searched (interrupted)"),
    "step": dict(facecolor="C1", alpha=0.45, label="uncertified: trace step"),
    "corner": dict(facecolor="C4", alpha=0.45, label="uncertified: cell corner"),
    "budget": dict(facecolor="C5", alpha=0.45, label="uncertified: step budget"),
    "pairing": dict(facecolor="C6", alpha=0.45, label="uncertified: pole-line pairing"),
    "polish": dict(facecolor="C8", alpha=0.45, label="uncertified: unpolished sign change"),
}
UNCERTIFIED_ZORDER = 2.5  # above the contours (2), below the markers (3)


def _shade_uncertified(ax, regions, w, unsearched_cells=None):
    """Each uncertified region a rectangle (clipped to the window), one collection per cause (gid
    "uncertified_<cause>"), labelled with its cause and count: of regions, or for "interrupted" of the cells not
    searched when unsearched_cells (the result's stats) is given (the label counted the merged rectangles, 49, while
    the run reported 4 666 cells; found by an attack on issue 13)."""
    from matplotlib.collections import PatchCollection
    from matplotlib.patches import Rectangle
    by_cause = {}
    for u in regions:
        lo1, hi1 = max(u["t1_lo"], w["t1_min"]), min(u["t1_hi"], w["t1_max"])
        lo2, hi2 = max(u["t2_lo"], w["t2_min"]), min(u["t2_hi"], w["t2_max"])
        if lo1 < hi1 and lo2 < hi2:
            by_cause.setdefault(u["cause"], []).append(Rectangle((lo1, lo2), hi1 - lo1, hi2 - lo2))
    proxies = []
    for cause, rects in by_cause.items():
        style = dict(UNCERTIFIED_STYLES.get(cause, dict(facecolor="0.3", alpha=0.45, label=f"uncertified: {cause}")))
        if cause == "interrupted" and unsearched_cells:
            label = style.pop("label") + f": {unsearched_cells} cells"
        else:
            label = style.pop("label") + f" ({len(rects)} region{'s' if len(rects) > 1 else ''})"
        ax.add_collection(PatchCollection(rects, edgecolor="none", zorder=UNCERTIFIED_ZORDER,
                                          gid=f"uncertified_{cause}", **style))
        proxies.append(Patch(label=label, **style))  # (a PatchCollection has no legend entry of its own)
    return proxies


def root_map_figure(system, solutions, window, points=400, path=None, ax=None, progress=None, uncertified=None,
                    numbers=True, computed=None, fig=None):
    """Root map of the window like the paper's Fig. 4: zero curves of eq. (5.1a) (det H = 0, solid) and of eq. (5.1b)
    (det P^T H P = 0 on z-perp, dashed) from spp.root_map, pole lines faint, and the SPPs (solutions of a result:
    anything with t1, t2, admissible) marked, potential open, admissible filled, each numbered with its index in
    `solutions` (the # of spp solve's table and the JSON's solution number; numbers=False: none). An SPP is where a
    dashed curve touches a solid one. window: dict with t1_min, t1_max, t2_min, t2_max (or a SolveResult, or that
    4-tuple); uncertified: the regions of a result (SolveResult.uncertified: dicts with t1_lo, t1_hi, t2_lo, t2_hi,
    cause), shaded with their cause in the legend (default: those of `window` when it is a SolveResult), e.g. the part
    an interrupted search did not reach; points: grid points per axis; ax: axes to draw into, or fig: a Figure to
    fill (cleared first); default a new figure;
    progress: spp.root_map's (True: a line on stderr, a callable: called with RootMapProgress; Ctrl-C raises
    KeyboardInterrupt, no figure drawn). The legend is outside the axes (below), so that it covers nothing.
    computed: a RootMap of this window already computed (spp.root_map(system, ...)), drawn as it is (points and
    progress unused): a notebook redraws without sampling again (a 20-dof box is a minute of evaluations)."""
    _checked(ax, fig)  # (before the map is sampled)
    if uncertified is None:
        uncertified = getattr(window, "uncertified", None) or []
    w = _window(window)
    if computed is not None:
        from ._spp import RootMap
        if not isinstance(computed, RootMap):
            raise TypeError(f"root_map_figure: computed must be a RootMap (spp.root_map), got "
                            f"{type(computed).__name__}")
        if computed.unsampled_cells:
            raise ValueError(f"root_map_figure: computed: expected a complete RootMap, got one interrupted with "
                             f"{computed.unsampled_cells} cell(s) not sampled")
        rm = computed
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)  # the interrupted map's warning: raised below instead
            rm = root_map(system, w["t1_max"], w["t2_max"], t1_min=w["t1_min"], t2_min=w["t2_min"], t1_points=points,
                          t2_points=points, progress=progress)
    if rm.unsampled_cells:  # Ctrl-C: no figure of part of the window
        raise KeyboardInterrupt(f"root map interrupted: {rm.unsampled_cells} cell(s) not sampled")
    fig, ax, own = _axes(ax, (COLUMN_WIDTH_IN * 1.5, COLUMN_WIDTH_IN * 1.5), fig)
    for p in rm.flight_poles:
        ax.axvline(p, color="0.8", lw=0.5, zorder=0)
    for p in rm.contact_poles:
        ax.axhline(p, color="0.8", lw=0.5, zorder=0)
    t1, t2, symmetric, onset = _merged_cells(rm)
    for values, style in ((symmetric, dict(colors="C0", linewidths=0.9)),
                          (onset, dict(colors="C2", linewidths=0.8, linestyles="--"))):
        if np.nanmin(values) < 0 < np.nanmax(values):
            ax.contour(t1, t2, np.ma.masked_invalid(values), levels=[0.0], **style)
    stats = getattr(window, "stats", None)
    shaded = _shade_uncertified(ax, uncertified, w, stats.get("unsearched_cells") if isinstance(stats, dict) else None)
    solutions = list(solutions)
    _scatter_spps(ax, solutions, lambda s: s.t1, lambda s: s.t2)
    ax.set_xlim(w["t1_min"], w["t1_max"])
    ax.set_ylim(w["t2_min"], w["t2_max"])
    ax.set_xlabel("flight half-duration $t_1$ (-)")
    ax.set_ylabel("contact half-duration $t_2$ (-)")
    handles = [Line2D([], [], color="C0", lw=0.9, label=r"(5.1a) $\det H = 0$"),
               Line2D([], [], color="C2", lw=0.8, ls="--", label=r"(5.1b) $\det P^\top H P = 0$"),
               Line2D([], [], color="0.8", lw=0.5, label="pole lines")]
    handles += ax.get_legend_handles_labels()[0] + shaded
    ax.legend(handles=handles, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, frameon=False)
    if own:
        _lay_out(fig)
    if numbers:  # the table's index beside each marker (gid "spp_number"), placed once the axes have their size
        inside = [(k, sol) for k, sol in enumerate(solutions)
                  if w["t1_min"] <= sol.t1 <= w["t1_max"] and w["t2_min"] <= sol.t2 <= w["t2_max"]]
        _place_numbers(ax, inside)
    return _save(fig, path)


NUMBER_FONTSIZE = 6  # the SPP numbers of the root map (5 was unreadable at the column width)


def _place_numbers(ax, numbered):
    """Each SPP's number (numbered: (k, solution) pairs) beside its marker, at the first of 16 offsets (up right,
    down right, up left, down left, above, below, right, left, then the same twice as far) where its box overlaps no
    number placed before, no other marker and stays inside the axes; where none does, at the offset of least
    overlap. (Every number up right of its marker overlapped its neighbours' on the paper's chain: 12/14, 35/40,
    46/48; found by an attack on issue 13.) Display units, so this is done after the figure's layout."""
    fig = ax.figure
    texts = [ax.annotate(str(k), (sol.t1, sol.t2), xytext=(2.5, 2.5), textcoords="offset points", ha="left",
                         va="bottom", fontsize=NUMBER_FONTSIZE, color="C3" if sol.admissible else "0.3", zorder=4,
                         gid="spp_number") for k, sol in numbered]
    if not texts:
        return
    renderer = getattr(fig.canvas, "get_renderer", None)
    if renderer is not None:
        renderer = renderer()
    else:  # Figure() without pyplot, svg/pdf canvases: text measured by Agg at the figure's dpi (the same metrics);
        # the numbers overlapped there (found by an attack)
        from matplotlib.backends.backend_agg import RendererAgg
        root = fig.figure
        renderer = RendererAgg(int(root.bbox.width), int(root.bbox.height), root.dpi)
    px = fig.dpi / 72.0  # display pixels per point
    frame = ax.get_window_extent(renderer)
    centres = ax.transData.transform([(sol.t1, sol.t2) for _, sol in numbered])
    mark = 2.5 * px  # half the marker's size (s=16: 4 pt across), with a margin
    markers = np.column_stack([centres - mark, centres + mark])  # x0, y0, x1, y1
    placed = []

    def overlap(a, b):
        return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))

    for i, (t, (x, y)) in enumerate(zip(texts, centres)):
        ext = t.get_window_extent(renderer)
        wd, ht = ext.width, ext.height
        gap = 2.5 * px
        best = None
        for far in (1.0, 2.0):
            g = gap * far
            for dx, dy in ((g, g), (g, -g - ht), (-g - wd, g), (-g - wd, -g - ht), (-wd / 2, g + mark),
                           (-wd / 2, -g - mark - ht), (g + mark, -ht / 2), (-g - mark - wd, -ht / 2)):
                box = (x + dx, y + dy, x + dx + wd, y + dy + ht)
                cost = sum(overlap(box, b) for b in placed)
                cost += sum(overlap(box, m) for j, m in enumerate(markers) if j != i)
                if box[0] < frame.x0 or box[2] > frame.x1 or box[1] < frame.y0 or box[3] > frame.y1:
                    cost += 0.5 * wd * ht  # outside the axes: clipped, or over the labels
                if best is None or cost < best[0]:
                    best = (cost, dx, dy, box)
                if cost == 0:
                    break
            if best[0] == 0:
                break
        t.xyann = (best[1] / px, best[2] / px)
        placed.append(best[3])


def frequency_energy_figure(solutions, path=None, ax=None, fig=None):
    """Frequency 2 pi / T against energy of SPPs (solutions of a result: anything with period, energy,
    admissible); admissible ones filled. ax: axes to draw into, or fig: a Figure to fill (cleared first); default a
    new figure."""
    sols = list(solutions)
    fig, ax, own = _axes(ax, (COLUMN_WIDTH_IN, 2.8), fig)
    _frequency_energy_spps(ax, sols, "transversally stable (Floquet)")
    # Below the axes, as the root map's: inside them "best" still covered chain5's SPP #0 (E = 20, f = 0.956).
    ax.legend(fontsize=7, frameon=False, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=2,
              handletextpad=0.2, columnspacing=1.0)
    if own:
        _lay_out(fig)
    return _save(fig, path)


def multipliers_figure(solutions, path=None, ax=None, fig=None):
    """Floquet multipliers (docs/stability.md) of the admissible SPPs in the complex plane, with the unit circle:
    one colour per SPP, its index in `solutions` (the result's solution index: the # of README's and docs/stability.md's
    tables for an admissible-only solve) and spectral radius in the legend; filled markers for stable SPPs, open for
    the others (their verdict, unstable / undecided / neutral, in the legend). The two structural multipliers 1 and the two zeros are drawn too. solutions: Solution objects
    (with floquet_multipliers); ax: axes to draw into, or fig: a Figure to fill (cleared first); default a new
    figure."""
    sols = [(k, s) for k, s in enumerate(solutions) if s.admissible and len(s.floquet_multipliers)]
    fig, ax, own = _axes(ax, (1.7 * COLUMN_WIDTH_IN, 1.1 * COLUMN_WIDTH_IN), fig)
    th = np.linspace(0.0, 2 * np.pi, 400)
    ax.plot(np.cos(th), np.sin(th), color="0.5", lw=0.8, gid="unit_circle")
    for i, (k, s) in enumerate(sols):
        mu = np.asarray(s.floquet_multipliers)
        style = (dict(color=f"C{i % 10}") if s.stable else dict(facecolors="none", edgecolors=f"C{i % 10}"))
        ax.scatter(mu.real, mu.imag, s=18, lw=0.9, zorder=3, gid=f"spp_{k}",
                   label=f"#{k}: $\\rho$ = {s.spectral_radius:.4f}" + ("" if s.stable else f" ({s.stability_verdict})"),
                   **style)
    ax.set_aspect("equal")
    ax.axhline(0, color="0.85", lw=0.5, zorder=0)
    ax.axvline(0, color="0.85", lw=0.5, zorder=0)
    ax.set_xlabel(r"Re $\mu$")
    ax.set_ylabel(r"Im $\mu$")
    if sols:
        ax.legend(fontsize=6, frameon=False, loc="center left", bbox_to_anchor=(1.0, 0.5))
    if own:
        _lay_out(fig)
    return _save(fig, path)


def modes_figure(result, solutions=(), path=None, ax=None, admissible_spps_only=True, fig=None):
    """Frequency-energy plot of the nonsmooth modes (docs/modes.md): the backbone of every k-IPP family of a
    spp.modes() result (genuine families solid, coloured by k, gid "k<k>"; repetitions of a shorter orbit thin grey
    dashes, gid "repetition"), the linear frequencies omega_j as dotted lines (gid "linear"), and the SPPs of
    `solutions` (solve() solutions or result candidates) as markers, a ring around the transversally stable ones."""
    fig, ax, own = _axes(ax, (COLUMN_WIDTH_IN * 1.4, 3.2), fig)
    ks = sorted({f.k for f in result.families})
    colors = {k: f"C{i % 10}" for i, k in enumerate(ks)}
    labelled = set()
    for f in result.families:
        a = f.arrays
        keep = a[:, 2] >= 0
        if not keep.any():
            continue
        if f.multiplicity > 1:
            ax.plot(a[keep, 0], a[keep, 1], "--", color="0.6", lw=0.6, gid="repetition",
                    label=None if "rep" in labelled else "repetition of a shorter orbit")
            labelled.add("rep")
        else:
            ax.plot(a[keep, 0], a[keep, 1], "-", color=colors[f.k], lw=1.1, gid=f"k{f.k}",
                    label=None if f.k in labelled else f"{f.k}-IPP")
            labelled.add(f.k)
    for w in result.linear_frequencies:
        ax.axhline(w, ls=":", color="0.3", lw=0.6, gid="linear")
    sols = [s for s in solutions if s.admissible or not admissible_spps_only]
    _frequency_energy_spps(ax, sols, "transversally stable SPP")
    ax.legend(fontsize=6, frameon=False, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    if own:
        _lay_out(fig)
    return _save(fig, path)
