"""`Status`: the one enumeration of outcomes, for points, curves, modes and designs.

Sweeps, maps, tables, cycles, planetary modes and studies all report an integer
``status`` per point or design; they all use these codes, so that a code means the same
thing in every file ballcvt writes (NetCDF and CSV ``status`` columns, a study's store).
A leaf: imports no physics.
"""

from __future__ import annotations

from enum import IntEnum

__all__ = ["Status"]


class Status(IntEnum):
    """Outcome of a solved point or an evaluated design."""

    #: Solved within every limit (a point), or evaluated (a design).
    CONVERGED = 0
    #: Solved, but beyond the limiting torque or the creep limit (flagged, not an answer).
    BEYOND_LIMIT = 1
    #: No equilibrium met the solver's tolerance.
    NOT_CONVERGED = 2
    #: The operating point is outside what the drive or the mode can reach.
    OUT_OF_RANGE = 3
    #: The design cannot be built (a study's design refused by the parameter checks).
    CANNOT_BE_BUILT = 4
    #: A study's design violates one of its constraints.
    CONSTRAINT_VIOLATED = 5

    @property
    def label(self) -> str:
        """The code's name as written in files (``beyond_limit``)."""
        return self.name.lower()

    @classmethod
    def flag_attributes(cls, members) -> dict:
        """CF ``flag_values`` and ``flag_meanings`` of the given members."""
        members = list(members)
        return {
            "flag_values": [int(m) for m in members],
            "flag_meanings": " ".join(m.label for m in members),
        }
