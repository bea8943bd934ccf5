"""spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact oscillators.

Same concepts and names as the C++ library: System (or System.from_json, chain, rod_with_slip, two_dof),
solve (SolveOptions, or its fields as keywords), nearest_spp, trajectory, simulate, verify, root_map, load_result, ParametricSystem and continue_branches. Arrays are numpy;
invalid input raises ValueError with the C++ message.
"""
from ._spp import __version__
from ._spp import (Branch, BranchEvent, BranchPoint, ContinuationResult, Event, NearestSpp, ParametricSystem, RootMap,
                   RootMapCell, SimulationResult, Solution, SolveOptions, SolveResult, SppCandidate, SppCheck,
                   Symmetry, System,
                   VerifyResult, chain, continue_branches, load_result, rod_with_slip, root_map, simulate, solve,
                   two_dof, verify, nearest_spp, fundamental_box, modal_frequencies, trajectory, SolveProgress)

__all__ = ["System", "Solution", "SolveOptions", "Symmetry", "SolveResult", "Event", "SimulationResult", "SppCheck", "VerifyResult",
           "SppCandidate", "RootMap", "RootMapCell", "chain", "rod_with_slip", "two_dof", "solve", "simulate",
           "verify", "load_result", "root_map", "ParametricSystem", "continue_branches", "Branch", "BranchEvent",
           "BranchPoint", "ContinuationResult", "nearest_spp", "NearestSpp", "fundamental_box", "modal_frequencies",
           "trajectory", "SolveProgress", "__version__"]
