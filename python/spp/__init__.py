"""spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact oscillators.

Same concepts and names as the C++ library: System (or System.from_json, chain, rod_with_slip, two_dof), solve,
nearest_spp, solution_at, trajectory, simulate, verify, root_map, load_result, ParametricSystem and
continue_branches. Each function takes its options struct (SolveOptions, SimulateOptions, VerifyOptions,
RootMapOptions, ContinueOptions) or any of its fields as keywords; options and results pickle. Arrays are numpy;
invalid input raises ValueError with the C++ message.
"""
from ._spp import __version__
from ._spp import Cancel  # cancel= of every long call: stops it from any thread
from ._spp import (Branch, BranchEvent, BranchEventKind, BranchPoint, ContinuationResult, ContinuationStatus,
                   ContinueOptions, Event, EventKind, NearestSpp, ParametricSystem, RootMap, RootMapCell,
                   RootMapOptions, RootMapProgress, SimulateOptions, SimulationResult, SimulationStatus, Solution, SolveOptions,
                   SolveProgress, SolveResult, SolveStatus, SppCheck, Symmetry, System, Verdict,
                   VerifyOptions, VerifyResult, VerifyStatus, chain, continue_branches, fundamental_box, load_result,
                   modal_frequencies, nearest_spp, rod_with_slip, root_map, simulate, trajectory, two_dof, verify)
from ._spp import continue_branch  # the one branch through a given SPP
from ._spp import ModeEvent, ModeEventKind, ModeFamily, ModePoint, ModesProgress, ModesResult, ModesStatus, modes  # k-IPP families (docs/modes.md)
from ._spp import SolutionAt, solution_at  # the SPP at a given (t1, t2), no search
from ._spp import monodromy  # linearised one-period map under an impact law (docs/stability.md)
from ._spp import MultiplierCrossing, StabilityVerdict  # the verdict with its rounding bound; crossing kinds
from . import _spp
from ._progress import Bar as _Bar
from ._sweep import sweep  # one solve per parameter value or system file: mpi4py or a process pool
from ._args import named_constructor_type_errors as _named_constructor_type_errors
from ._args import named_type_errors as _named_type_errors
from . import _frames

# every bound function and constructor: an argument of the wrong type is named (spp._args)
for _name, _value in list(globals().items()):
    if type(_value).__name__ == "builtin_function_or_method" and getattr(_value, "__module__", "") == "spp._spp":
        globals()[_name] = _named_type_errors(_value, f"spp.{_name}")
    elif isinstance(_value, type) and _value.__module__ == "spp._spp":
        if "__init__" in vars(_value):
            _named_constructor_type_errors(_value)
        if "from_json" in vars(_value):  # System.from_json(pathlib.Path(...)) and the like
            setattr(_value, "from_json",
                    staticmethod(_named_type_errors(_value.from_json, f"spp.{_name}.from_json")))
_solve = _named_type_errors(_spp.solve, "spp.solve")

# one row per SPP, check or branch point (pandas), each column with its dtype (spp._frames)
SolveResult.to_dataframe = _frames.solve_result_frame
VerifyResult.to_dataframe = _frames.verify_result_frame
ContinuationResult.to_dataframe = _frames.continuation_result_frame
Branch.to_dataframe = _frames.branch_frame
ModesResult.to_dataframe = _frames.modes_result_frame
ModeFamily.to_dataframe = _frames.mode_family_frame
# a notebook's view of every result type (SolveResult has its own table)
for _type in (VerifyResult, ContinuationResult, Branch, RootMap, SimulationResult, Solution, NearestSpp,
              ModesResult, ModeFamily, ModePoint, ModeEvent, SolutionAt):
    _type._repr_html_ = _frames.repr_html


def _reduce_ex(self, protocol):
    # pybind11's pickling needs protocol 2 or higher: protocols 0 and 1 aborted the interpreter (an uncatchable
    # std::runtime_error "instance allocation failed", found by an attack), so they are a TypeError here
    if protocol < 2:
        raise TypeError(f"spp.{type(self).__name__} pickles with protocol 2 or higher (pickle's default is 4), "
                        f"got protocol {protocol}")
    return object.__reduce_ex__(self, protocol)


for _type in vars(_spp).values():  # every picklable class (the ones bound with __getstate__)
    if isinstance(_type, type) and "__getstate__" in vars(_type):
        _type.__reduce_ex__ = _reduce_ex


_nearest_spp = _named_type_errors(_spp.nearest_spp, "spp.nearest_spp")
_root_map = _named_type_errors(_spp.root_map, "spp.root_map")


def _with_progress(name, run, progress, *args, **fields):
    """run(*args, progress=..., **fields) with progress="bar" drawn by spp._progress.Bar (named after `name`)."""
    if isinstance(progress, str):
        if progress != "bar":
            raise ValueError(f"{name}: progress must be True, False, None, a callable or \"bar\", got {progress!r}")
        with _Bar(desc=f"spp {name}") as bar:
            return run(*args, progress=bar, **fields)
    if progress is None:
        return run(*args, **fields)
    return run(*args, progress=progress, **fields)


def solve(system, options=None, progress=None, **fields):
    return _with_progress("solve", _solve, progress, system, options, **fields)


def nearest_spp(system, t1, t2, radius=0.05, options=None, progress=None, **fields):
    return _with_progress("nearest_spp", _nearest_spp, progress, system, t1, t2, radius, options, **fields)


def root_map(system, t1_max=None, t2_max=None, options=None, progress=None, **fields):
    return _with_progress("root_map", _root_map, progress, system, t1_max, t2_max, options, **fields)


solve.__doc__ = _spp.solve.__doc__ + (
    "\n\nprogress=\"bar\": a progress bar (tqdm's, a widget in Jupyter, when python3-tqdm is installed; else a "
    "text bar on stderr): cells traced / cells of the window, SPP candidates so far, ETA.")
nearest_spp.__doc__ = _spp.nearest_spp.__doc__ + "\n\nprogress=\"bar\": a progress bar as solve's."
root_map.__doc__ = _spp.root_map.__doc__ + "\n\nprogress=\"bar\": a progress bar (cells sampled / cells, ETA)."

__all__ = ["System", "Solution", "SolveOptions", "Symmetry", "SolveResult", "Event", "SimulateOptions",
           "SimulationResult", "SppCheck", "VerifyOptions", "VerifyResult", "RootMap", "RootMapCell",
           "RootMapOptions", "RootMapProgress", "chain", "rod_with_slip", "two_dof", "solve", "simulate", "verify", "load_result",
           "root_map", "ParametricSystem", "continue_branches", "ContinueOptions", "Branch", "BranchEvent",
           "BranchPoint", "ContinuationResult", "continue_branch", "nearest_spp", "NearestSpp", "fundamental_box", "modal_frequencies",
           "trajectory", "SolveProgress", "SolveStatus", "SimulationStatus", "EventKind", "VerifyStatus", "Verdict",
           "ContinuationStatus", "BranchEventKind", "monodromy", "StabilityVerdict", "MultiplierCrossing", "modes", "ModesResult", "ModeFamily",
           "ModePoint", "ModeEvent", "ModeEventKind", "ModesStatus", "ModesProgress", "sweep", "solution_at", "SolutionAt", "Cancel", "__version__"]
