"""The moments about a ball's tilt and skew axes at a solved point (docs/model.md §17).

From an equilibrium problem and its solved state: the contacts as `ballcvt.model.shift`
takes them (`tilt_contacts`), and the steady point's moments per ball (`steady_moments`),
which `make_result` stores on every `OperatingResult` and the shift-effort analysis uses.
"""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import EquilibriumState
from ..model.kinematics import creep_term
from ..model.shift import TiltContacts, skew_axis_moment, tilt_moments
from ..model.traction.base import traction_law
from ..model.traction.contact import ContactState
from ..model.traction.quadrature import Quadrature

__all__ = ["tilt_contacts", "steady_moments"]


def tilt_contacts(
    problem: EquilibriumProblem, state: EquilibriumState, quadrature: Quadrature
) -> TiltContacts:
    """The solved contacts of ``problem`` at ``state``, carrier frame.

    Each film enters at the edge its surfaces come from, ``sign(kappa_c rho_c omega_S)``
    along Eq. 55's ``x`` (`TiltContacts.entry`); the normals are the layout's.
    """
    pb, st, lay = problem, state, problem.layout
    contacts = ContactState(
        creep_term(st.creep),
        st.spin,
        pb.ax,
        pb.ay,
        pb.p_max,
        pb.load,
        pb.radius,
        st.u_ref,
        st.film,
    )
    entry = np.sign(lay.kappa * pb.rho * np.asarray(st.omega_s)[..., None])
    return TiltContacts(
        contacts,
        lay.kappa,
        pb.design.roller_radius,
        pb.fluid,
        quadrature,
        entry,
        (lay.z_j, lay.z_k),
    )


def steady_moments(
    problem: EquilibriumProblem, state: EquilibriumState, quadrature: Quadrature
) -> tuple[np.ndarray, np.ndarray]:
    """Holding moment and moment about the skew axis per ball at zero tilt rate [N m].

    The holding moment is `ballcvt.model.shift.tilt_moments` at rate 0 (the film's
    lateral force at zero side slip; zero under a law whose lateral force is odd in the
    side slip, ``TractionLaw.odd_lateral``; NaN under a registered traction law without a
    side-slip form, ``TractionLaw.lateral``); the skew moment is
    `ballcvt.model.shift.skew_axis_moment` of the solver's own tractions and spin moments
    (``state.force``, ``state.moment``), so it closes the ball's moment balance:
    ``M_k = -sin(gamma) M_s + cos(gamma) M_u``.
    """
    lay, law = problem.layout, traction_law(problem.fluid)
    if getattr(law, "lateral", None) is None:
        holding = np.full(np.shape(state.omega_s), np.nan)
    elif getattr(law, "odd_lateral", False):  # no lateral force without side slip
        holding = np.zeros(np.shape(state.omega_s))
    else:
        holding = tilt_moments(tilt_contacts(problem, state, quadrature), 0.0).holding
    skew = skew_axis_moment(
        state.force, state.moment, lay.z_j, lay.z_k, problem.design.roller_radius
    )
    return holding, skew
