"""Sweeps: one solve per parameter value of a parametric system file, or per system file (spp sweep's library,
include/spp/distributed/sweep.hpp), spread over MPI ranks with mpi4py when the script runs under mpirun, else over a
concurrent.futures thread pool on this machine (each item's solve releases the GIL).

Each item's result is written to its own file in ``out_dir`` (atomically, as ``spp solve --json`` writes it); a sweep
run again resumes from the files already there (outcome "resumed"); a failing item is reported in the table (outcome
"failed" and its message), never fatal to the others. The table of every SPP with its value is written to
``out_dir/sweep.csv`` and ``out_dir/sweep.json`` and returned (the JSON, as a dict).

Under ``mpirun -n P python3 script.py`` (mpi4py, Debian python3-mpi4py) rank 0 hands the items out and the other
P - 1 ranks solve them (mpi4py.futures.MPICommExecutor); ``sweep`` returns the table on rank 0 and None on the others.
"""
import concurrent.futures
import json
import math
import numbers
import os
import warnings

from . import _spp

_MPI_ENV = ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK")


def _world():
    """MPI_COMM_WORLD when this process runs under mpirun with more than one rank and mpi4py is there, else None.
    (mpi4py is not imported otherwise: importing it initialises MPI.)"""
    if not any(v in os.environ for v in _MPI_ENV):
        return None
    try:
        from mpi4py import MPI
    except ImportError:
        return None
    comm = MPI.COMM_WORLD
    return comm if comm.Get_size() > 1 else None


def _run_item(spec, index):
    """One item, from picklable arguments (runs on a worker thread or on another rank)."""
    return _spp._sweep_item(spec["systems"], spec["parameter"], spec["values"], spec["out_dir"], index,
                            **spec["fields"])


def _checked_values(values):
    """values as a list of floats: a list (tuple, array, range) of real numbers; a str, a single number, a bool
    are refused naming the argument (values='25' swept 2.0 and 5.0, the characters; found by an independent attack).
    A "start:stop:step" text as spp sweep --values takes is not read here: Python gives the list itself."""
    if values is None:
        return None
    if isinstance(values, (str, bytes)):
        raise TypeError(f"sweep: values must be a list of numbers, got the text {values[:80]!r} (a 'start:stop:step' "
                        "text is not read in Python: give the list, e.g. [1 + 0.25 * i for i in range(37)] or "
                        "numpy.linspace(1, 10, 37))")
    if isinstance(values, numbers.Number) or not hasattr(values, "__iter__"):
        raise TypeError(f"sweep: values must be a list of numbers, got the {type(values).__name__} {values!r} "
                        f"(one value: [{values!r}])")
    out = []
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise TypeError(f"sweep: values[{i}] must be a real number, got the {type(v).__name__} {v!r}")
        if not math.isfinite(float(v)):
            raise ValueError(f"sweep: values[{i}] must be finite, got {float(v)!r}")
        out.append(float(v))
    if not out:
        raise ValueError("sweep: values is empty: expected at least one number")
    return out


def _checked_workers(workers):
    """None, or a whole number >= 1 (0, -1 and 1.5 were clamped to a number of threads; now refused)."""
    if workers is None:
        return None
    if isinstance(workers, bool) or not isinstance(workers, numbers.Integral):
        raise TypeError(f"sweep: workers must be a whole number >= 1 or None, got the {type(workers).__name__} "
                        f"{workers!r}")
    if workers < 1:
        raise ValueError(f"sweep: workers must be >= 1 (or None: one per core), got {int(workers)}")
    return int(workers)


def sweep(systems, out_dir, parameter=None, values=None, workers=None, **fields):
    """One solve per value of ``parameter`` (``values``: a list of numbers) of the parametric system file
    ``systems`` (one path), or per system file (``systems``: a list of paths, no parameter), each result written to
    ``out_dir``. ``fields``: SolveOptions fields (``t1_max`` and ``t2_max`` required; ``threads`` per solve).

    Without MPI: ``workers`` threads, each solving one item at a time (default: os.cpu_count() // threads, at least 1; each solve then gets
    ``threads`` threads, default os.cpu_count() // workers) so that workers x threads does not oversubscribe the
    cores. Returns the table (the dict of out_dir/sweep.json: "parameter", "items" with each item's "outcome",
    "message", "solve_status" and "spps"). Raises, before any solve and any file written: TypeError for values that
    are not a list of real numbers (a str such as "1:10:0.25" is not read: give the list) or workers not a whole
    number; ValueError for workers < 1, a bad plan (a missing or read-only out_dir, another parameter name, no value,
    a value not finite) or result files in out_dir of another system, window or options (a resume that would mix
    results). A value outside the parameter's declared range gives a warning (UserWarning).
    """
    if isinstance(systems, (str, os.PathLike)):
        systems = [systems]
    systems = [os.fspath(s) for s in systems]
    out_dir = os.fspath(out_dir)
    values = _checked_values(values)
    workers = _checked_workers(workers)
    items = _spp._sweep_items(systems, parameter, values, out_dir)  # checks the plan (ValueError) on every rank
    notes = _spp._sweep_check(systems, parameter, values, out_dir, **fields)  # out_dir writable, resumable
    cores = os.cpu_count() or 1
    comm = _world()
    if comm is not None:
        fields.setdefault("threads", 1)
        spec = dict(systems=systems, parameter=parameter, values=values, out_dir=out_dir, fields=fields)
        from mpi4py.futures import MPICommExecutor
        with MPICommExecutor(comm, root=0) as executor:
            if executor is None:  # a worker rank: it served items until the root was done
                return None
            for note in notes:
                warnings.warn("sweep: " + note, stacklevel=2)
            outcomes = list(executor.map(_run_item, [spec] * len(items), range(len(items))))
    else:
        for note in notes:
            warnings.warn("sweep: " + note, stacklevel=2)
        threads = int(fields.get("threads", 0))
        if workers is None:
            workers = max(1, cores // threads) if threads > 0 else cores
        workers = max(1, min(int(workers), len(items)))
        if threads == 0:
            fields["threads"] = max(1, cores // workers)
        spec = dict(systems=systems, parameter=parameter, values=values, out_dir=out_dir, fields=fields)
        with _spp._SingleThreadedBlas(), concurrent.futures.ThreadPoolExecutor(max_workers=workers) as executor:
            outcomes = list(executor.map(lambda i: _run_item(spec, i), range(len(items))))
    text, _ = _spp._sweep_table(systems, parameter, values, out_dir, [o for o, _ in outcomes],
                                [m for _, m in outcomes], os.path.join(out_dir, "sweep.csv"),
                                os.path.join(out_dir, "sweep.json"))
    return json.loads(text)
