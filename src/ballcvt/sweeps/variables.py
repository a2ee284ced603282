"""Names, units and long names of every variable a sweep writes (CF-style attributes)."""

from __future__ import annotations

__all__ = ["VARIABLES", "POINT_VARIABLES", "CONTACT_VARIABLES", "STATUS", "attrs_for"]

#: ``status`` values.
STATUS = {"converged": 0, "beyond_limit": 1, "not_converged": 2}

#: name -> (units, long name)
VARIABLES = {
    "ratio": ("1", "ideal speed ratio tau_ID"),
    "output_torque": ("N m", "output torque T_2"),
    "clamp_force": ("N", "clamping force at the input contact F_N0"),
    "input_speed": ("rad/s", "input speed omega_0"),
    "limit_torque": ("N m", "limiting output torque (all |creep| <= creep_limit)"),
    "status": ("1", "point status: 0 converged, 1 beyond limiting torque, 2 not converged"),
    "iterations": ("1", "solver iterations (residual-and-Jacobian evaluations)"),
    "residual_norm": ("1", "max |residual| of the equilibrium at the solution"),
    "eta": ("1", "overall efficiency (Eq. 38)"),
    "eta_losses": ("1", "overall efficiency from the power losses (Eq. 39)"),
    "eta_speed": ("1", "speed efficiency (Eq. 9)"),
    "eta_torque": ("1", "torque efficiency (Eq. 37)"),
    "input_torque": ("N m", "input torque T_0"),
    "actual_ratio": ("1", "actual speed ratio omega_2 / omega_0"),
    "tilt": ("degree", "ball tilt angle gamma"),
    "loss_total": ("W", "total power loss (Eq. 40)"),
    "loss_creep": ("W", "creep power loss, all contacts"),
    "loss_spin": ("W", "spin power loss, all contacts"),
    "loss_bearing": ("W", "bearing power loss"),
    "creep": ("1", "creep coefficient C (Eq. 7)"),
    "spin": ("1", "spin coefficient sigma (Eqs. 11-14)"),
    "mu": ("1", "traction coefficient mu (Eq. 30)"),
    "chi": ("1", "spin-moment coefficient chi (Eq. 31)"),
    "p_max": ("Pa", "Hertz peak pressure"),
    "film_thickness": ("m", "central film thickness (Hamrock-Dowson)"),
    "normal_load": ("N", "contact normal load F_N"),
    "contact_loss": ("W", "creep plus spin power loss of the contact, all balls"),
}

POINT_VARIABLES = ("eta", "eta_losses", "eta_speed", "eta_torque", "input_torque",
                   "actual_ratio", "tilt", "loss_total", "loss_creep", "loss_spin",
                   "loss_bearing")
CONTACT_VARIABLES = ("creep", "spin", "mu", "chi", "p_max", "film_thickness", "normal_load",
                     "contact_loss")


def attrs_for(name: str) -> dict:
    """``{"units": ..., "long_name": ...}`` of a variable (and the flags of ``status``)."""
    units, long_name = VARIABLES[name]
    attrs = {"units": units, "long_name": long_name}
    if name == "status":
        attrs.update(flag_values=list(STATUS.values()), flag_meanings=" ".join(STATUS))
    return attrs
