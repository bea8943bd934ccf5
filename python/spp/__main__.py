"""python3 -m spp plot|animate: figures and animations of a result of `spp solve --json` (also run by `spp plot`
and `spp animate`).

plot RESULT.json --out DIR [--solutions admissible|all|0,3,5]: DIR/root_map.*, DIR/frequency_energy.* and
DIR/spp_K.* for each chosen SPP K (default: the admissible ones).
animate RESULT.json --out FILE.gif|FILE.mp4 [--solution K]: one SPP over its period.
"""
import argparse
import os
import shutil
import sys
import tempfile

EXIT_INTERRUPTED = 130  # Ctrl-C, as spp solve and a shell report it
EXIT_USAGE = 1  # invalid input and usage errors, as every spp subcommand
ARGPARSE_USAGE_ERROR = 2  # what argparse exits with on a usage error


MAX_ROOT_MAP_POINTS = 4000  # per axis: 1.6e7 grid values per condition, minutes of evaluations; the default is 400


def _plot(a):
    from . import plot
    import matplotlib.pyplot as plt
    formats = [f.strip() for f in a.formats.split(",") if f.strip()]
    bad = [f for f in formats if f not in ("png", "svg", "pdf")]
    if bad or not formats:
        raise ValueError(f"--formats: expected png, svg or pdf, got {a.formats!r}")
    if a.root_map_points != 0 and not 16 <= a.root_map_points <= MAX_ROOT_MAP_POINTS:
        raise ValueError(f"--root-map-points must be 0 (no root map) or in [16, {MAX_ROOT_MAP_POINTS}], "
                         f"got {a.root_map_points}")
    if os.path.exists(a.out) and not os.path.isdir(a.out):
        raise ValueError(f"--out {a.out}: exists and is not a directory (plot writes its figures into a directory)")
    from ._spp import load_result
    r = load_result(a.result)
    system, spps, window = r.system, list(r.solutions), dict(t1_min=r.t1_min, t1_max=r.t1_max, t2_min=r.t2_min,
                                                                t2_max=r.t2_max)
    chosen = _chosen(a.solutions, spps, a.result)
    # created only now that every option and the result are read; removed again if this run made it and fails. The
    # figures are drawn into a staging directory inside it and moved in only once all are drawn: a failure half-way
    # (a system the modal form refuses, Ctrl-C) leaves no part of a set behind, and earlier figures untouched
    # (found by an independent attack).
    created = not os.path.exists(a.out)
    os.makedirs(a.out, exist_ok=True)
    staging = tempfile.mkdtemp(prefix=".spp-plot-", dir=a.out)
    written = []
    moved = []

    def save(fig, name):
        for fmt in formats:
            p = os.path.join(staging, f"{name}.{fmt}")
            plot.save_atomic(fig, p)
            written.append(p)
        plt.close(fig)

    try:
        try:
            if a.root_map_points:
                # the root map is the long part (a 20-dof box: 10^5 points): its progress line on a terminal
                save(plot.root_map_figure(system, spps, window, points=a.root_map_points,
                                          progress=sys.stderr.isatty(), uncertified=r.uncertified), "root_map")
            save(plot.frequency_energy_figure(spps), "frequency_energy")
            for k in chosen:
                save(plot.spp_figure(system, spps[k]), f"spp_{k}")
        except ValueError as e:  # e.g. the modal form refusing the embedded system: name the file it came from
            if str(e).startswith(a.result):
                raise
            raise ValueError(f"{a.result}: {e}") from None
        for p in written:
            os.replace(p, os.path.join(a.out, os.path.basename(p)))
            moved.append(os.path.join(a.out, os.path.basename(p)))
    except BaseException:
        for p in moved:  # a failure while moving in: the figures already moved go too (no partial set)
            try:
                os.remove(p)
            except OSError:
                pass
        shutil.rmtree(staging, ignore_errors=True)
        if created:
            try:
                os.rmdir(a.out)
            except OSError:
                pass
        raise
    shutil.rmtree(staging, ignore_errors=True)
    print(f"wrote {len(written)} figures to {a.out}")


def _chosen(text, spps, result):
    """Indices of the SPPs to draw: 'admissible', 'all', or a comma-separated list of 0-based indices."""
    if text == "admissible":
        return [k for k, s in enumerate(spps) if s.admissible]
    if text == "all":
        return list(range(len(spps)))
    try:
        ks = [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(f"--solutions: expected admissible, all or indices like 0,3,5, got {text!r}") from None
    bad = [k for k in ks if not 0 <= k < len(spps)]
    if bad or not ks:
        raise ValueError(f"--solutions {text}: {result} has {len(spps)} solutions (0..{len(spps) - 1})")
    repeated = sorted({k for k in ks if ks.count(k) > 1})
    if repeated:  # each index names one file: a repeat drew it twice and failed moving it in (attack on issue 13)
        raise ValueError(f"--solutions {text}: expected each index once, got {', '.join(map(str, repeated))} "
                         "more than once")
    return ks


def _animate(a):
    from . import animate
    animate.check_options(a.out, frames=a.frames, periods=a.periods, fps=a.fps, dpi=a.dpi, layout=a.layout)
    out_dir = os.path.dirname(os.path.abspath(a.out))
    if not os.path.isdir(out_dir):
        raise ValueError(f"--out {a.out}: the directory {out_dir} does not exist")
    from ._spp import load_result
    r = load_result(a.result)
    system, spps = r.system, list(r.solutions)
    if a.solution < 0:
        admissible = [k for k, s in enumerate(spps) if s.admissible]
        if not admissible:
            raise ValueError(f"{a.result}: no admissible SPP; choose one with --solution K (0..{len(spps) - 1})")
        k = admissible[0]
    elif a.solution >= len(spps):
        raise ValueError(f"--solution {a.solution}: {a.result} has {len(spps)} solutions (0..{len(spps) - 1})")
    else:
        k = a.solution
    # (read here to name the result file when the layout is not one of its system)
    fe_layout = animate.FeLayout.read(a.fe_layout, system, a.result) if a.fe_layout else None
    frames = animate.animate(system, spps[k], a.out, frames=a.frames, periods=a.periods, fps=a.fps, dpi=a.dpi,
                             layout=a.layout, fe_layout=fe_layout)
    layout = "fe" if a.fe_layout else animate.layout_of(system) if a.layout == "auto" else a.layout
    print(f"wrote {a.out}: solution {k}, {frames} frames, layout {layout}")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="spp", description="figures and animations of a result of spp solve")
    sub = ap.add_subparsers(dest="command", required=True)
    p = sub.add_parser("plot", help="root map, one figure per admissible SPP, frequency-energy")
    p.add_argument("result", help="result JSON of spp solve --json")
    p.add_argument("--out", required=True, help="output directory (created if missing)")
    p.add_argument("--formats", default="png,svg", help="comma-separated: png, svg, pdf (default png,svg)")
    p.add_argument("--root-map-points", type=int, default=400, help="grid points per axis; 0: no root map")
    p.add_argument("--solutions", default="admissible",
                   help="SPPs drawn one figure each: admissible (default), all, or indices like 0,3,5 (each once)")
    q = sub.add_parser("animate", help="animation of one SPP (GIF, or MP4 with ffmpeg)")
    q.add_argument("result", help="result JSON of spp solve --json")
    q.add_argument("--out", required=True, help="output file, .gif or .mp4")
    q.add_argument("--solution", type=int, default=-1, help="index in the result (default: first admissible)")
    q.add_argument("--frames", type=int, default=120, help="frames per period (default 120)")
    q.add_argument("--periods", type=int, default=1)
    q.add_argument("--fps", type=int, default=25)
    q.add_argument("--dpi", type=int, default=125, help="the frame is 6.4 x 4.8 inches (default 125: 800 x 600)")
    q.add_argument("--layout", default="auto", help="auto, chain, plane, dofs or fe (with --fe-layout)")
    q.add_argument("--fe-layout", default=None,
                   help="a layout file (spp generate bar's, spp reduce --layout's): draw the finite-element model")
    try:
        a = ap.parse_args(argv)
    except SystemExit as e:  # argparse exits 2 on a usage error; spp's usage errors exit 1 (README "Exit codes")
        return EXIT_USAGE if e.code == ARGPARSE_USAGE_ERROR else e.code
    try:
        import matplotlib
        matplotlib.use("Agg")  # headless: files only (the library modules leave the backend alone)
        _plot(a) if a.command == "plot" else _animate(a)
    except KeyboardInterrupt:
        # Ctrl-C: one line, no traceback (it printed 47 lines), and nothing half-written (the figures are staged and
        # the animation written to a temporary name: both removed on the way out)
        print("interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except ValueError as e:
        print(f"spp: error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # a file that cannot be written (permissions, a full disk): its name and the reason
        where = f"{e.filename}: " if e.filename else ""
        print(f"spp: error: {where}{e.strerror or e}", file=sys.stderr)
        return 1
    except MemoryError:
        print("spp: error: out of memory: fewer points, frames or a lower dpi bound the work", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except KeyboardInterrupt:  # before main's own handler (while Python imports the package)
        print("interrupted", file=sys.stderr)
        sys.exit(EXIT_INTERRUPTED)
