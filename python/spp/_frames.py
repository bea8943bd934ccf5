"""to_dataframe() of SolveResult, VerifyResult, ContinuationResult and Branch: one row per SPP, per check or per
branch point, each column with its own dtype (an empty result keeps them: bool for admissible, int for counts).
SolveResult's columns are those of ``spp solve --csv`` (src/io/csv.cpp: t1 ... stability_verdict, x0_1 .. x0_n,
v0_1 .. v0_n), then flags."""
import numpy as np


def _pandas():
    try:
        import pandas
    except ImportError:
        raise ImportError("to_dataframe needs pandas (Debian: apt-get install python3-pandas)") from None
    return pandas


def _frame(columns, rows):
    """columns: [(name, dtype)]; rows: lists of values in that order."""
    pd = _pandas()
    data = {}
    for j, (name, dtype) in enumerate(columns):
        data[name] = np.array([row[j] for row in rows], dtype=dtype) if rows else np.array([], dtype=dtype)
    return pd.DataFrame(data, columns=[c[0] for c in columns])


def solve_result_frame(r):
    """One row per SPP in the result's order (by period): the columns of spp solve --csv (t1, t2, period, admissible,
    min_gap, min_force, energy, residual, return_error, spectral_radius, stable, spectral_radius_error,
    stability_verdict, x0_1 .. x0_n, v0_1 .. v0_n) with the dtypes pandas.read_csv gives them (bool for admissible and
    stable, written true/false), then flags (comma-separated). Needs pandas."""
    sols = list(r.solutions)
    n = len(sols[0].x0) if sols else (r.system.n if hasattr(r, "system") and hasattr(r.system, "n") else 0)
    columns = [("t1", float), ("t2", float), ("period", float), ("admissible", bool), ("min_gap", float),
               ("min_force", float), ("energy", float), ("residual", float), ("return_error", float),
               ("spectral_radius", float), ("stable", bool), ("spectral_radius_error", float),
               ("stability_verdict", object)]
    columns += [(f"x0_{i}", float) for i in range(1, n + 1)] + [(f"v0_{i}", float) for i in range(1, n + 1)]
    columns.append(("flags", object))
    rows = [[x.t1, x.t2, x.period, x.admissible, x.min_gap, x.min_force, x.energy, x.residual, x.return_error,
             x.spectral_radius, x.stable, x.spectral_radius_error, str(x.stability_verdict)] + list(x.x0) +
            list(x.v0) + [",".join(x.flags)] for x in sols]
    return _frame(columns, rows)


def verify_result_frame(v):
    """One row per SPP checked: t1, t2, admissible (the solver's), verdict, consistent, periods_followed,
    return_error (after the first period), potential_return_error, departure_time, departure, impacts,
    contact_onsets, releases, growth_per_period (NaN where there is none: departure_time of an SPP that never leaves
    its orbit, growth_per_period without a perturbation; they read 0.0, a time and a growth that did not happen;
    found by an attack on issue 13). Needs pandas."""
    columns = [("t1", float), ("t2", float), ("admissible", bool), ("verdict", object), ("consistent", bool),
               ("periods_followed", np.int64), ("return_error", float), ("potential_return_error", float),
               ("departure_time", float), ("departure", object), ("impacts", np.int64), ("contact_onsets", np.int64),
               ("releases", np.int64), ("growth_per_period", float)]
    rows = []
    for c in v.checks:
        first = c.return_errors[0] if len(c.return_errors) else float("nan")
        departed = c.departure_time if c.departure else float("nan")
        growth = c.growth_per_period if len(c.perturbed_distances) else float("nan")
        rows.append([c.t1, c.t2, c.admissible, str(c.verdict), c.consistent, c.periods_followed, first,
                     c.potential_return_error, departed, c.departure, c.impacts, c.contact_onsets, c.releases, growth])
    return _frame(columns, rows)


_POINT_COLUMNS = [("mu", float), ("t1", float), ("t2", float), ("period", float), ("admissible", bool),
                  ("margin", float), ("closure", float), ("energy", float), ("spectral_radius", float)]


def _point_row(p):
    return [p.mu, p.t1, p.t2, p.period, p.admissible, p.margin, p.closure, p.energy, p.spectral_radius]


def branch_frame(b):
    """One row per point of the branch, in the order traced: mu, t1, t2, period, admissible, margin, closure, energy,
    spectral_radius. Needs pandas."""
    return _frame(_POINT_COLUMNS, [_point_row(p) for p in b.points])


def continuation_result_frame(c):
    """One row per point of every branch: branch (its index in c.branches), then the columns of
    Branch.to_dataframe(). Needs pandas."""
    rows = [[i] + _point_row(p) for i, b in enumerate(c.branches) for p in b.points]
    return _frame([("branch", np.int64)] + _POINT_COLUMNS, rows)


_MODE_POINT_COLUMNS = [("energy", float), ("frequency", float), ("period", float), ("impacts", np.int64),
                       ("admissible", bool), ("margin", float), ("multiplicity", np.int64)]


def _mode_point_row(p):
    return [p.energy, p.frequency, p.period, len(p.impact_times), p.admissible, p.margin, p.multiplicity]


def mode_family_frame(f):
    """One row per point of the family, in the order traced: energy, frequency (2 pi / period), period, impacts (k),
    admissible, margin, multiplicity. Needs pandas."""
    return _frame(_MODE_POINT_COLUMNS, [_mode_point_row(p) for p in f.points])


def modes_result_frame(r):
    """One row per point of every family: family (its index in r.families), label, k, symmetry, mode (1-based),
    family_multiplicity, then the columns of ModeFamily.to_dataframe(). Needs pandas."""
    columns = [("family", np.int64), ("label", object), ("k", np.int64), ("symmetry", object), ("mode", np.int64),
               ("family_multiplicity", np.int64)] + _MODE_POINT_COLUMNS
    rows = [[i, f.label, f.k, f.symmetry, f.mode, f.multiplicity] + _mode_point_row(p)
            for i, f in enumerate(r.families) for p in f.points]
    return _frame(columns, rows)


HTML_ROWS = 20  # rows of to_dataframe() shown in a notebook cell; the rest are counted (SolveResult's own table: 20)


def repr_html(obj):
    """A notebook's view of a result (_repr_html_, one helper for every type that has none of its own): its repr,
    escaped, then the first HTML_ROWS rows of its to_dataframe() when it has one and pandas is installed. (Only
    SolveResult had a view; found by an attack on issue 13.)"""
    import html
    out = f"<p>{html.escape(repr(obj))}</p>"
    to_frame = getattr(obj, "to_dataframe", None)
    if to_frame is not None:
        try:
            df = to_frame()
        except ImportError:  # no pandas: the repr alone
            return out
        out += df.head(HTML_ROWS).to_html()
        if len(df) > HTML_ROWS:
            out += f"<p>({len(df) - HTML_ROWS} more rows: to_dataframe())</p>"
    return out
