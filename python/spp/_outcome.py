"""Base of the result enums (SolveStatus, SimulationStatus, VerifyStatus, Verdict, ContinuationStatus, EventKind,
BranchEventKind): each member is its C++ to_string name, and a str, so that ``r.status is spp.SolveStatus.success``,
``r.status == "success"``, ``print(r.status)`` (prints ``success``) and ``json.dumps(r.status)`` all work."""
import enum


class Outcome(str, enum.Enum):
    """A result's status or kind: compares equal to, prints and serialises as its name."""
    __str__ = str.__str__
    __format__ = str.__format__

    def __repr__(self):
        return f"{type(self).__name__}.{self.name}"
