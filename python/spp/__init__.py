"""spp: periodic orbits with one lasting contact phase per period (SPPs) of vibro-impact oscillators.

Same concepts and names as the C++ library: System (or System.from_json, chain, rod_with_slip, two_dof),
solve, simulate, verify. Arrays are numpy; invalid input raises ValueError with the C++ message.
"""
from ._spp import (Event, SimulationResult, Solution, SolveResult, SppCheck, System, VerifyResult, chain,
                   rod_with_slip, simulate, solve, two_dof, verify)

__all__ = ["System", "Solution", "SolveResult", "Event", "SimulationResult", "SppCheck", "VerifyResult",
           "chain", "rod_with_slip", "two_dof", "solve", "simulate", "verify"]
