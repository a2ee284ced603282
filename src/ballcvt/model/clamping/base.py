"""Clamping laws: what a law is, and how a name resolves to one (docs/model.md §11).

A clamping law answers one question: the input-contact normal load ``F_N0`` [N] at given
disc torques. A law is a subclass of `ClampLaw` registered by name in
`ballcvt.registry.CLAMP_LAWS`; the solvers, sweeps, cycles and studies read its
properties, never its name:

* ``name`` (str);
* ``implicit`` (bool): the force depends on the input torque ``T_0``, which the
  equilibrium determines (solved with it, `ballcvt.solvers.clamped`);
* ``fixed_force`` (bool): the force is a given number, the same at every torque (a
  sweep's clamping force is then a dimension);
* ``optimises`` (bool): the force is chosen per point for the best efficiency
  (`ballcvt.solvers.optimal_clamp`), not given by a force law;
* ``clamp_force(design, input_torque, output_torque)`` -> ``F_N0`` [N];
* ``output_torque_bound(design, clamp_force, ratio)`` -> the largest ``T_2`` [N m] at which
  the law's force stays at or below ``clamp_force`` (the capacity search's upper end);
* ``resolve(design, clamp_force)`` (class method) -> the law a name stands for, built
  from the design (and the force, for a law with ``fixed_force``).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np

from ...errors import InputError
from ...params.models import Design
from ...registry import CLAMP_LAWS

__all__ = [
    "ClampLaw",
    "CLAMP_LAWS",
    "DEFAULT_LAW",
    "axial_force",
    "clamp_law",
    "names_fixed_force",
    "refuse_force",
]

#: The law a missing ``clamp_law`` stands for (the paper's fixed clamping force).
DEFAULT_LAW = "constant"


def names_fixed_force(law) -> bool:
    """Whether ``law`` as given (None, a registered name or a law object) is the fixed-force
    law by default or by name; an unknown name is an `InputError` listing the laws."""
    return law is None or (isinstance(law, str) and CLAMP_LAWS.get(law).fixed_force)


def axial_force(design: Design, clamp_force):
    """Axial thrust on each disc ``F_D0 = n F_N0 sin(theta_0)`` [N] (docs/model.md §1).

    Parameters
    ----------
    design : Design
        Drive geometry.
    clamp_force : array_like
        Input-contact normal load ``F_N0`` [N].

    Returns
    -------
    ndarray or float
        Disc thrust [N]; the output disc carries the same (``F_N2 sin theta_2 =
        F_N0 sin theta_0``, Eq. 29).
    """
    return design.n_rollers * np.asarray(clamp_force, dtype=float) * math.sin(design.theta0)


def refuse_force(name: str, clamp_force) -> None:
    """`InputError` if ``clamp_force`` is given to the law ``name``, which sets it."""
    if clamp_force is not None:
        raise InputError(
            "clamp_force",
            clamp_force,
            f"not given with clamp_law {name!r} (the law sets the clamping force)",
        )


class ClampLaw:
    """Base of the clamping laws: the defaults of the interface (module docstring).

    A subclass sets ``name`` and defines ``clamp_force`` and ``output_torque_bound``;
    ``resolve`` builds it with no arguments (``from_design``) unless overridden.
    """

    name: str = ""
    #: The force is a given number, the same at every torque.
    fixed_force: ClassVar[bool] = False
    #: The force is chosen per point by optimisation, not given by a force law.
    optimises: ClassVar[bool] = False
    #: The force depends on the input torque (solved with the equilibrium).
    implicit: bool = False

    @classmethod
    def from_design(cls, design: Design) -> Any:
        """The law for ``design`` (default: the class's defaults)."""
        return cls()

    @classmethod
    def resolve(cls, design: Design, clamp_force=None) -> Any:
        """The law the registered name stands for; ``clamp_force`` [N] must not be given
        unless the law has ``fixed_force``."""
        refuse_force(cls.name, clamp_force)
        return cls.from_design(design)

    def clamp_force(self, design: Design, input_torque, output_torque):
        """``F_N0`` [N] at the disc torques [N m]."""
        raise NotImplementedError

    def output_torque_bound(self, design: Design, clamp_force, ratio):
        """Largest ``T_2`` [N m] whose force stays at or below ``clamp_force`` [N]."""
        raise NotImplementedError


def clamp_law(law, design: Design, clamp_force=None):
    """Resolve a law given by name or object, with the force of a fixed-force law.

    Parameters
    ----------
    law : str, law object or None
        A name in `ballcvt.registry.CLAMP_LAWS` (None: ``"constant"``), or a law object.
    design : Design
        Drive (for the parameters a law reads from it, e.g. the cam's).
    clamp_force : float, optional
        ``F_N0`` [N] of the constant law; must not be given with another law.

    Returns
    -------
    ClampLaw
        ``CLAMP_LAWS.get(law).resolve(design, clamp_force)``, or the object given.
    """
    if law is None or isinstance(law, str):
        return CLAMP_LAWS.get(DEFAULT_LAW if law is None else law).resolve(design, clamp_force)
    refuse_force(getattr(law, "name", str(law)), clamp_force)
    return law
