"""Animations of an SPP over its period (matplotlib.animation): GIF with Pillow, MP4 with ffmpeg when installed.

The picture follows the system's structure, read from M, K and w (no extra metadata needed):
  - "chain": M diagonal, K tridiagonal (springs between neighbours and to the ground), w on one dof: masses as
    boxes along a line, zigzag springs, the obstacle as a wall at the contact dof, the contact force as an arrow;
  - "plane": w on exactly two dofs (the rod with slip of §5.3: x2, y2 of its contact node): the contact point in
    that plane, the oblique obstacle line w_i x_i + w_j x_j + g0 = 0, its path, and the force along the normal;
    beside it, every dof as a bar;
  - "dofs": anything else: every dof's position as a stem plot;
  - "fe": given a finite-element layout (fe_layout=, a file of `spp generate bar` or `spp reduce --layout`, or one
    written for any model: include/spp/io/layout_file.hpp): the model itself, its nodes moved by the SPP's
    displacements (of a reduced model: expanded to the full model's dofs by the reduction basis in the file); 1-D
    coordinates: the displacement along the model against the position; 2-D (or the first two of 3-D): the deformed nodes over the undeformed ones,
    displacements scaled to a tenth of the model's size; the obstacle where the contact dof is among the dofs drawn.
Below each picture, gap (left axis) and contact force (right axis, its own scale) with a cursor. The curves are
those of spp.plot.spp_figure: the SPP's own equations (spp.trajectory, exact flows), so that an inadmissible SPP is
shown as the potential orbit it is (contact 2 t2, then flight 2 t1 through the obstacle), its violations shaded and
named, not as what the simulator does from its onset state (it leaves the orbit at the first impact); time origin at
contact onset, flight on [-2 t1, 0] and contact on [0, 2 t2], as in the static figure.
"""
import os
import shutil

import numpy as np

import matplotlib.pyplot as plt
from matplotlib import animation

from ._files import atomic_path
from . import plot as _plot
from . import _spp

LAYOUTS = ("auto", "chain", "plane", "dofs", "fe")
FIGSIZE_IN = (6.4, 4.8)  # every frame
MAX_DPI = 600  # 3840 x 2880 pixels a frame; beyond, matplotlib's renderer fails (dpi 100000: an IndexError)
MAX_FRAMES = 10000  # frames x periods: 400 s at 25 fps, each frame drawn by matplotlib (~20 ms)
# A GIF's frames are held in memory until the file is written (matplotlib's PillowWriter): RGBA, 4 bytes a pixel.
# 800 x 600 frames, as the docs' GIFs: at the former 80 (512 x 384) the legend's text was ~4 px high, unreadable
# (found by an attack on issue 13)
DEFAULT_DPI = 125
MAX_GIF_BYTES = 2 * 1024 ** 3


def check_options(path, frames=120, periods=1, fps=25, dpi=DEFAULT_DPI, layout="auto", figsize=FIGSIZE_IN):
    """Raises ValueError naming the option when an animation of these options is not possible or would not fit in
    memory; called before anything is computed or allocated."""
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in (".gif", ".mp4"):
        raise ValueError(f"{path}: the animation file must end in .gif or .mp4")
    if ext == ".mp4" and shutil.which("ffmpeg") is None:
        raise ValueError(f"{path}: MP4 needs ffmpeg (apt-get install ffmpeg); write a .gif instead")
    for name, value, lo, hi in (("frames", frames, 2, MAX_FRAMES), ("periods", periods, 1, MAX_FRAMES // 2),
                                ("fps", fps, 1, 1000), ("dpi", dpi, 20, MAX_DPI)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not lo <= value <= hi:
            raise ValueError(f"{name} must be an integer in [{lo}, {hi}], got {value!r}")
    if frames * periods > MAX_FRAMES:
        raise ValueError(f"frames x periods must be at most {MAX_FRAMES} (each frame is drawn by matplotlib), got "
                         f"{frames} x {periods} = {frames * periods}")
    if ext == ".gif":
        frame_bytes = 4 * round(figsize[0] * dpi) * round(figsize[1] * dpi)
        if frames * periods * frame_bytes > MAX_GIF_BYTES:
            raise ValueError(f"{path}: {frames * periods} frames of {frame_bytes / 2 ** 20:.3g} MiB (dpi {dpi}) are "
                             f"more than the {MAX_GIF_BYTES // 2 ** 30} GiB a GIF may hold in memory while written: "
                             f"fewer frames or periods, a lower dpi, or an .mp4")
    if layout not in LAYOUTS:
        raise ValueError(f"layout must be one of {', '.join(LAYOUTS)}, got {layout!r}")



def layout_of(system):
    """'chain', 'plane' or 'dofs' (see the module's docstring)."""
    M, K, w = system.M, system.K, system.w
    n = system.n
    scale = max(np.abs(K).max(), 1e-300)
    support = np.flatnonzero(np.abs(w) > 1e-12)
    tridiagonal = all(abs(K[i, j]) <= 1e-12 * scale for i in range(n) for j in range(n) if abs(i - j) > 1)
    diagonal_mass = np.allclose(M, np.diag(np.diag(M)), atol=1e-12 * np.abs(M).max())
    if n >= 1 and len(support) == 1 and diagonal_mass and tridiagonal:
        return "chain"
    if len(support) == 2:
        return "plane"
    return "dofs"


def _zigzag(x0, x1, y, coils=6, width=0.12):
    t = np.linspace(0.0, 1.0, 2 * coils + 3)
    xs = x0 + (x1 - x0) * t
    ys = np.full_like(t, y)
    ys[1:-1] += width * np.where(np.arange(1, len(t) - 1) % 2, 1.0, -1.0)
    ys[1] = ys[-2] = y
    return xs, ys


class _Chain:
    """Masses at rest positions 1..n (ground at 0), displacements scaled so that the largest is 0.35."""

    def __init__(self, ax, system, x, force):
        n = system.n
        self.c = int(np.flatnonzero(np.abs(system.w) > 1e-12)[0])
        wc = system.w[self.c]
        self.s = 0.35 / max(np.abs(x).max(), abs(system.g0 / wc), 1e-300)
        self.rest = np.arange(1, n + 1, dtype=float)
        # g = wc x_c + g0 >= 0: the obstacle sits where x_c = -g0 / wc, on the side of -sign(wc).
        self.wall = self.rest[self.c] + self.s * (-system.g0 / wc)
        self.side = -np.sign(wc)
        self.fmax = max(force.max(), 1e-300)
        h = 0.18
        ax.plot([0, 0], [-0.5, 0.5], color="k", lw=2)
        ax.fill_betweenx([-0.5, 0.5], -0.15, 0, color="0.85", hatch="///", lw=0)
        wall_x = self.wall + self.side * h
        ax.plot([wall_x, wall_x], [-0.45, 0.45], color="k", lw=2.5)
        ax.fill_betweenx([-0.45, 0.45], wall_x, wall_x + 0.12 * self.side, color="0.85", hatch="///", lw=0)
        self.springs = [ax.plot([], [], color="0.3", lw=1)[0] for _ in range(n)]
        self.boxes = [plt.Rectangle((0, -h), 2 * h, 2 * h, fc="C0", ec="k", lw=0.8, zorder=3) for _ in range(n)]
        for b in self.boxes:
            ax.add_patch(b)
        self.arrow = ax.annotate("", xy=(0, 0), xytext=(0, 0),
                                 arrowprops=dict(arrowstyle="-|>", color="C3", lw=2))
        self.h = h
        ax.set_xlim(-0.3, n + 1.0)
        ax.set_ylim(-0.9, 0.9)
        ax.set_aspect("equal")
        ax.axis("off")

    def draw(self, x, force):
        pos = self.rest + self.s * x
        left = 0.0
        for i in range(len(pos)):
            self.springs[i].set_data(*_zigzag(left, pos[i] - self.h, 0.0))
            self.boxes[i].set_xy((pos[i] - self.h, -self.h))
            left = pos[i] + self.h
        # The force pushes the contact mass away from the wall: arrow from the wall into the mass.
        length = 0.6 * force / self.fmax
        tip = self.wall + self.side * self.h
        self.arrow.set_position((tip, 0.32))
        self.arrow.xy = (tip - self.side * length, 0.32)
        self.arrow.set_visible(force > 0)
        return [*self.springs, *self.boxes, self.arrow]


class _Plane:
    """The contact point (x_i, x_j) in its plane, with the oblique obstacle; beside it, all dofs as bars."""

    def __init__(self, ax, system, x, force, bars_ax):
        self.i, self.j = np.flatnonzero(np.abs(system.w) > 1e-12)
        wi, wj = system.w[self.i], system.w[self.j]
        self.normal = np.array([wi, wj])  # unit (w is stored unit-length, and only these two are non-zero)
        self.normal /= np.linalg.norm(self.normal)
        pts = x[:, [self.i, self.j]]
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = 0.25 * max((hi - lo).max(), abs(system.g0), 1e-300)
        lo, hi = lo - pad, hi + pad
        # Obstacle line w_i a + w_j b + g0 = 0 across the box, forbidden side hatched.
        foot = -system.g0 * self.normal / np.linalg.norm([wi, wj])
        tangent = np.array([-self.normal[1], self.normal[0]])
        span = 2.0 * np.linalg.norm(hi - lo)
        a, b = foot - span * tangent, foot + span * tangent
        ax.plot([a[0], b[0]], [a[1], b[1]], color="k", lw=2)
        ax.fill([a[0], b[0], b[0] - span * self.normal[0], a[0] - span * self.normal[0]],
                [a[1], b[1], b[1] - span * self.normal[1], a[1] - span * self.normal[1]],
                color="0.85", hatch="///", lw=0, zorder=0)
        ax.plot(pts[:, 0], pts[:, 1], color="0.6", lw=0.8)
        self.dot = ax.plot([], [], "o", color="C0", ms=8, zorder=3)[0]
        self.arrow = ax.annotate("", xy=(0, 0), xytext=(0, 0),
                                 arrowprops=dict(arrowstyle="-|>", color="C3", lw=2))
        self.fmax = max(force.max(), 1e-300)
        self.len = 0.3 * (hi - lo).max()
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_aspect("equal")
        ax.set_xlabel(f"$x_{{{self.i + 1}}}$ (-)")
        ax.set_ylabel(f"$x_{{{self.j + 1}}}$ (-)")
        ax.set_title("contact point and obstacle", fontsize=8)
        self.bars = _Dofs(bars_ax, x)

    def draw(self, x, force):
        p = np.array([x[self.i], x[self.j]])
        self.dot.set_data([p[0]], [p[1]])
        self.arrow.set_position(tuple(p))
        self.arrow.xy = tuple(p + self.len * force / self.fmax * self.normal)
        self.arrow.set_visible(force > 0)
        return [self.dot, self.arrow, *self.bars.draw(x, force)]


class _Dofs:
    """Every dof's position as a stem plot, fixed limits over the period."""

    def __init__(self, ax, x):
        n = x.shape[1]
        self.k = np.arange(1, n + 1)
        lim = 1.1 * max(np.abs(x).max(), 1e-300)
        self.stems = ax.vlines(self.k, 0, np.zeros(n), color="C0", lw=2)
        self.tops = ax.plot(self.k, np.zeros(n), "o", color="C0", ms=4)[0]
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xlim(0.3, n + 0.7)
        ax.set_ylim(-lim, lim)
        ax.set_xlabel("dof (-)")
        ax.set_ylabel("position (-)")
        if n <= 12:
            ax.set_xticks(self.k)
        else:  # dof indices are whole numbers (past 12 the default ticks fell at 2.5, 7.5; attack on issue 13)
            from matplotlib.ticker import MaxNLocator
            ax.xaxis.set_major_locator(MaxNLocator(integer=True))

    def draw(self, x, force):
        self.stems.set_segments([[(k, 0.0), (k, v)] for k, v in zip(self.k, x)])
        self.tops.set_ydata(x)
        return [self.stems, self.tops]


# The layout reader is the C++ one (include/spp/io/layout_file.hpp), bound as spp.FeLayout: FeLayout.read(source,
# system) reads a path or the file's dict and checks it against the system it is drawn over (dofs beyond the system's,
# basis columns, the fingerprint of another reduced model: ValueError naming both). (A second reader here drifted
# from it.) What the drawing needs of it is added below.
FeLayout = _spp.FeLayout


class _FeLayoutDrawing:
    def displacements(self, x):
        """The listed dofs' displacements (samples x rows) from the system's positions x (samples x n)."""
        return x @ self.basis.T if self.basis is not None else x[:, self.dofs]

    def contact_row(self, system):
        """The row of the contact dof and the displacement at which the gap closes there (None, None when w is on
        several dofs or the contact dof is not listed): a row whose expansion is the unit vector of w's one dof."""
        support = np.flatnonzero(np.abs(system.w) > 1e-12)
        if len(support) != 1:
            return None, None
        c = support[0]
        rows = np.eye(system.n)[self.dofs] if self.basis is None else self.basis
        unit = np.zeros(system.n)
        unit[c] = 1.0
        hits = np.flatnonzero(np.abs(rows - unit).max(axis=1) <= 1e-12)
        if not len(hits):
            return None, None
        return int(hits[0]), -system.g0 / system.w[c]


FeLayout.displacements = _FeLayoutDrawing.displacements
FeLayout.contact_row = _FeLayoutDrawing.contact_row


class _Fe:
    """The model from its layout (FeLayout): 1-D, the displacement along the model against the position; 2-D (or
    3-D: the first two coordinates), the deformed nodes over the undeformed ones."""

    def __init__(self, ax, system, x, layout):
        self.layout = layout
        d = layout.displacements(x)  # samples x rows
        self.row, at = layout.contact_row(system)
        self.dim = layout.coordinates.shape[1]
        if self.dim == 1:
            self.order = np.argsort(layout.coordinates[:, 0], kind="stable")
            xs = layout.coordinates[self.order, 0]
            sign = np.sign(layout.directions[self.order, 0])
            self.sign = sign
            lim = 1.15 * max(np.abs(d).max(), abs(at) if at is not None else 0.0, 1e-300)
            ax.axhline(0.0, color="0.7", lw=0.8)
            self.line = ax.plot(xs, np.zeros_like(xs), "-", color="C0", lw=1.5, gid="fe_displacement")[0]
            if self.row is not None:
                xc = layout.coordinates[self.row, 0]
                level = at * np.sign(layout.directions[self.row, 0])
                width = 0.04 * max(np.ptp(xs), 1e-300)
                ax.plot([xc - width, xc + width], [level, level], color="k", lw=2.5, gid="obstacle")
                self.dot = ax.plot([], [], "o", color="C3", ms=5, zorder=3)[0]
            ax.set_xlim(xs.min() - 0.02 * np.ptp(xs), xs.max() + 0.02 * np.ptp(xs) + 1e-300)
            ax.set_ylim(-lim, lim)
            ax.set_xlabel("position along the model (-)")
            ax.set_ylabel("displacement (-)")
            ax.set_title(f"finite-element layout: {len(layout.dofs)} dofs", fontsize=8)
            return
        # the plane drawn: that of the two axes along which the dofs move most (a plate in x-y moving along z is
        # seen from the side, x-z: the first two axes showed it motionless; found by an attack), ties broken by the
        # nodes' spread
        scaled = layout.directions / np.abs(layout.directions).max(axis=1)[:, None]  # (no underflow of tiny ones)
        units = scaled / np.linalg.norm(scaled, axis=1)[:, None]
        axes = [(0, 1)] if self.dim == 2 else [(0, 1), (0, 2), (1, 2)]
        weight = lambda p: (np.linalg.norm(units[:, p], axis=1).sum(), np.ptp(layout.coordinates[:, p], axis=0).sum())
        self.plane = list(max(axes, key=weight))
        # nodes by their full coordinates (a side view must not merge nodes that differ in the hidden one), drawn in
        # the plane
        full, self.node_of = np.unique(layout.coordinates, axis=0, return_inverse=True)
        self.node_of = self.node_of.ravel()
        self.nodes = full[:, self.plane]
        c = layout.coordinates[:, self.plane]
        u = units[:, self.plane]
        self.u = u
        extent = max(np.ptp(self.nodes, axis=0).max(), 1e-300)
        peak = max(np.abs(self._node_displacement(d)).max(), 1e-300)
        self.scale = 0.1 * extent / peak
        ax.plot(self.nodes[:, 0], self.nodes[:, 1], ".", color="0.8", ms=3, gid="undeformed")
        self.cloud = ax.plot([], [], ".", color="C0", ms=4, gid="fe_displacement")[0]
        if self.row is not None:
            p = c[self.row] + self.scale * at * u[self.row]
            t = np.array([-u[self.row, 1], u[self.row, 0]]) * 0.05 * extent
            ax.plot([p[0] - t[0], p[0] + t[0]], [p[1] - t[1], p[1] + t[1]], color="k", lw=2.5, gid="obstacle")
        pad = 0.15 * extent
        ax.set_xlim(self.nodes[:, 0].min() - pad, self.nodes[:, 0].max() + pad)
        ax.set_ylim(self.nodes[:, 1].min() - pad, self.nodes[:, 1].max() + pad)
        ax.set_aspect("equal")
        names = "xyz"
        ax.set_xlabel(f"{names[self.plane[0]]} (-)")
        ax.set_ylabel(f"{names[self.plane[1]]} (-)")
        ax.set_title(f"finite-element layout: {len(self.nodes)} nodes, displacements x {self.scale:.3g}", fontsize=8)

    def _node_displacement(self, d):
        """Per node (samples x nodes x 2): the sum of its dofs' displacements along their directions."""
        out = np.zeros((d.shape[0], len(self.nodes), 2))
        for k in range(2):
            np.add.at(out[:, :, k], (slice(None), self.node_of), d * self.u[:, k])
        return out

    def draw(self, x, force):
        d = self.layout.displacements(x[None, :])
        if self.dim == 1:
            values = d[0, self.order] * self.sign
            self.line.set_ydata(values)
            if self.row is None:
                return [self.line]
            xc = self.layout.coordinates[self.row, 0]
            self.dot.set_data([xc], [d[0, self.row] * np.sign(self.layout.directions[self.row, 0])])
            return [self.line, self.dot]
        p = self.nodes + self.scale * self._node_displacement(d)[0]
        self.cloud.set_data(p[:, 0], p[:, 1])
        return [self.cloud]


def _frame_states(system, spp, times):
    """Positions (frames x n) and contact forces (frames,) at `times` (from contact onset, any real), exact: the SPP's
    own equations at those times (spp.trajectory(times=...)), or for a zero-gap SPP (g0 = 0, see
    spp.plot._one_period) the exact simulator sampled at those times modulo the period."""
    import warnings
    T = spp.period
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the interrupted run's warning: raised below instead
        if system.g0 != 0.0:
            tr = _spp.trajectory(system, spp.t1, spp.t2, times=times)
            if tr["interrupted"]:
                raise KeyboardInterrupt(f"trajectory interrupted: {len(tr['t'])} of {len(times)} frames")
            return tr["x"], tr["force"]
        phase = np.mod(times, T)
        sim = _spp.simulate(system, spp.x0, spp.v0, T, 0.0, sample_times=np.sort(phase), sample_events=False)
    if sim.status == "interrupted":
        raise KeyboardInterrupt("simulation interrupted")
    at = np.searchsorted(sim.t, phase)  # (its rows: t = 0, the times asked for, t = T)
    return sim.x[at], sim.force[at]


def _figure(system, spp, frames, periods, kind, fig=None, fe_layout=None):
    """The animation's figure, its frame function and frame count: one period of the SPP from spp.plot's
    _one_period (the SPP's own equations), on the static figure's time axis [-2 t1, 2 t2] (flight before contact),
    repeated for `periods`. fig: a matplotlib Figure to draw into (cleared first; its size is kept); default a new
    one of FIGSIZE_IN."""
    T, t1, t2 = spp.period, spp.t1, spp.t2
    count = frames * periods
    tr = _plot._one_period(system, spp, max(2000, 20 * frames))
    t = np.where(tr["t"] > 2 * t2, tr["t"] - T, tr["t"])  # the flight after the contact is the one before it
    order = np.argsort(t, kind="stable")
    t, x, gap, force = t[order], tr["x"][order], tr["gap"][order], tr["force"][order]
    keep = np.r_[True, np.diff(t) > 0]  # t = 2 t2 - T and t = -2 t1 are the same instant: once
    t, x, gap, force = t[keep], x[keep], gap[keep], force[keep]
    if periods > 1:
        t = np.concatenate([t + k * T for k in range(periods)])
        x, gap, force = (np.concatenate([a] * periods) for a in (x, gap, force))
    times = -2 * t1 + np.arange(count) * (T / frames)
    # each frame's state exactly at its time (the nearest sample was off by up to half a sample: issue 13)
    frame_x, frame_force = _frame_states(system, spp, times)

    if fig is None:
        fig = plt.figure(figsize=FIGSIZE_IN)
    else:
        fig.clf()
    grid = fig.add_gridspec(2, 2 if kind == "plane" else 1, height_ratios=[1.6, 1])
    if kind == "plane":
        scene = _Plane(fig.add_subplot(grid[0, 0]), system, x, force, fig.add_subplot(grid[0, 1]))
        hist = fig.add_subplot(grid[1, :])
    else:
        top = fig.add_subplot(grid[0, 0])
        if kind == "fe":
            scene = _Fe(top, system, x, fe_layout)
        else:
            scene = _Chain(top, system, x, force) if kind == "chain" else _Dofs(top, x)
        hist = fig.add_subplot(grid[1, 0])
    for k in range(periods):
        hist.axvspan(k * T, k * T + 2 * t2, color="0.9", lw=0, label="contact phase" if k == 0 else None)
    hist.plot(t, gap, color="C0", lw=1.2, label="gap $g$ (-)", gid="gap")
    hist.axhline(0.0, color="k", lw=0.6)
    hist.set_xlim(-2 * t1, 2 * t2 + (periods - 1) * T)
    hist.set_xlabel("time $t$ (-), 0 at contact onset")
    hist.set_ylabel("gap $g$ (-)", color="C0", fontsize=8)
    right = hist.twinx()  # the force has its own scale (at n = 20 the gap reaches 500 and the force 40)
    right.plot(t, force, color="C3", lw=1.2, label=r"force $\lambda$ (-)", gid="force")
    right.set_ylabel(r"contact force $\lambda$ (-)", color="C3", fontsize=8)
    # a potential SPP's violations of ineqs. (5.3), as in spp_figure: gap < 0 in flight, force < 0 in contact
    phase = np.mod(t, T)
    contact = phase <= 2 * t2
    scale_g, scale_f = max(np.abs(gap).max(), 1e-300), max(np.abs(force).max(), 1e-300)
    bad_gap, bad_force = ~contact & (gap < -1e-9 * scale_g), contact & (force < -1e-9 * scale_f)
    if bad_gap.any():
        hist.fill_between(t, gap, 0.0, where=bad_gap, color="red", alpha=0.35, lw=0, label="gap < 0 in flight",
                          gid="violation")
    if bad_force.any():
        right.fill_between(t, force, 0.0, where=bad_force, color="red", alpha=0.2, lw=0, hatch="//",
                           label="force < 0 in contact", gid="violation")
    _plot._align_zeros(hist, right)
    handles = hist.get_legend_handles_labels()[0] + right.get_legend_handles_labels()[0]
    hist.legend(handles=handles, fontsize=6, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=len(handles),
                frameon=False, borderaxespad=0.1)
    cursor = hist.axvline(times[0], color="k", lw=1)
    if spp.admissible:
        title = f"SPP $t_1$ = {spp.t1:.5g}, $t_2$ = {spp.t2:.5g}, $T$ = {T:.5g} (admissible)"
    else:  # what is shown is not a motion of the system: said in the title
        title = (f"potential SPP $t_1$ = {spp.t1:.5g}, $t_2$ = {spp.t2:.5g}, $T$ = {T:.5g}: NOT ADMISSIBLE\n"
                 "(its own equations, the obstacle ignored in flight: not a motion of the system)")
    fig.suptitle(title, fontsize=9, color="k" if spp.admissible else "C3")
    fig.tight_layout()

    def update(k):
        cursor.set_xdata([times[k], times[k]])
        return [cursor, *scene.draw(frame_x[k], frame_force[k])]

    return fig, update, count


def _kind(system, layout, fe_layout=None):
    if fe_layout is not None and layout not in ("auto", "fe"):
        raise ValueError(f"fe_layout is drawn with layout 'fe' (or 'auto'), got layout {layout!r}")
    if layout == "fe" and fe_layout is None:
        raise ValueError("layout 'fe' needs fe_layout (a layout file of spp generate bar / spp reduce --layout)")
    if fe_layout is not None:
        return "fe"
    kind = layout_of(system) if layout == "auto" else layout
    if kind == "chain" and layout_of(system) != "chain":
        raise ValueError("layout 'chain' needs a diagonal M, a tridiagonal K and w on one dof")
    if kind == "plane" and np.count_nonzero(np.abs(system.w) > 1e-12) != 2:
        raise ValueError("layout 'plane' needs w on exactly two dofs")
    return kind


def _whole_figure(fig):
    """fig as given: None or a matplotlib Figure (an animation redraws a whole figure, so not a SubFigure); anything
    else a TypeError naming it (it was an AttributeError from inside matplotlib; found by an attack)."""
    from matplotlib.figure import Figure
    if fig is not None and not isinstance(fig, Figure):
        raise TypeError(f"fig: expected a matplotlib Figure (plt.figure(); an animation redraws a whole figure, not "
                        f"a SubFigure or Axes), got {type(fig).__name__}")
    return fig


def animation_of(system, spp, frames=120, periods=1, fps=25, layout="auto", fig=None, fe_layout=None):
    """The animation of the SPP (anything with t1, t2, period, x0, v0) as a matplotlib FuncAnimation, written to no
    file: anim.to_jshtml() (or animation_html) shows it in Jupyter, anim.save(...) writes it. fig: a Figure to draw
    into (cleared; its size and dpi are kept), default a new one of FIGSIZE_IN; anim._fig is it. Raises ValueError
    on bad arguments (those of animate but the path and dpi)."""
    check_options("animation.gif", frames=frames, periods=periods, fps=fps, layout=layout)
    _whole_figure(fig)
    if fe_layout is not None:
        if isinstance(fe_layout, FeLayout):
            fe_layout.check(system)
        else:
            fe_layout = FeLayout.read(fe_layout, system)
    kind = _kind(system, layout, fe_layout)
    fig, update, count = _figure(system, spp, frames, periods, kind, fig, fe_layout)
    return animation.FuncAnimation(fig, update, frames=count, interval=1000.0 / fps, blit=False)


class AnimationHTML(str):
    """The HTML of an animation (a str): a Jupyter cell whose value it is shows the animation (_repr_html_)."""

    def _repr_html_(self):
        return str(self)

    # Short text forms: Jupyter stores text/plain beside text/html, and the whole HTML as text/plain doubled the
    # notebook's size (found by an attack).
    def __repr__(self):
        return f"<AnimationHTML: {len(self) / 1e6:.2f} MB of HTML (shown as an animation in Jupyter)>"

    def _repr_pretty_(self, p, cycle):
        p.text(repr(self))


def animation_html(system, spp, frames=60, periods=1, fps=25, layout="auto", fig=None, embed_limit_mb=None,
                   fe_layout=None):
    """The animation of the SPP as HTML with its frames embedded and play controls (matplotlib's to_jshtml): the
    value of a Jupyter cell shows it inline, whatever the backend. Each frame is a PNG at the figure's dpi (default
    figure: 640 x 480 at dpi 100), about 40-80 kB, so the default 60 frames are a few MB in the notebook.
    embed_limit_mb: matplotlib's rcParams["animation.embed_limit"] (default 20 MB) for this call; past it matplotlib
    drops frames with a warning. The figure is closed afterwards (unless given as fig), so that the cell does not
    also show its last frame. Returns an AnimationHTML (a str with _repr_html_)."""
    import matplotlib
    own = fig is None
    anim = animation_of(system, spp, frames=frames, periods=periods, fps=fps, layout=layout, fig=fig,
                        fe_layout=fe_layout)
    try:
        limit = {} if embed_limit_mb is None else {"animation.embed_limit": float(embed_limit_mb)}
        with matplotlib.rc_context(limit):
            return AnimationHTML(anim.to_jshtml(fps=fps))
    finally:
        if own:
            plt.close(anim._fig)


def animate(system, spp, path, frames=120, periods=1, fps=25, dpi=DEFAULT_DPI, layout="auto", fig=None,
            fe_layout=None):
    """Writes an animation of the SPP (anything with t1, t2, period, x0, v0) to path: .gif (Pillow) or .mp4
    (ffmpeg). frames: per period. fig: a Figure to draw into (cleared; its size is kept; not closed), default a new
    one of FIGSIZE_IN (closed when written). Returns the number of frames written. Raises ValueError on bad
    arguments. In a notebook, animation_html shows it inline instead."""
    figsize = FIGSIZE_IN if _whole_figure(fig) is None else tuple(fig.get_size_inches())
    check_options(path, frames=frames, periods=periods, fps=fps, dpi=dpi, layout=layout, figsize=figsize)
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    own = fig is None
    anim = animation_of(system, spp, frames=frames, periods=periods, fps=fps, layout=layout, fig=fig,
                        fe_layout=fe_layout)
    writer = animation.PillowWriter(fps=fps) if ext == ".gif" else animation.FFMpegWriter(fps=fps)
    try:
        with atomic_path(path) as tmp:
            anim.save(tmp, writer=writer, dpi=dpi)
    finally:
        if own:
            plt.close(anim._fig)
    return frames * periods
