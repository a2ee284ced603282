"""Design values that look like unit mistakes, naming the field and the value likely
meant: a length in millimetres given as metres is refused, an angle in radians given as
degrees is warned of (`ballcvt.errors.UnitHintWarning`; a contact angle of about one
degree is a feasible, if extreme, geometry: tests/test_feasibility.py).

Such values lie inside a field's own bounds (an angle of 0.785 deg is > 0, a ball radius
of 3.5 m is < 10 m) and would otherwise fail much later, in the solver, with messages
about creep or clamping force that do not point at the input.
"""

from __future__ import annotations

import math
import warnings

from ..errors import InputError, UnitHintWarning

__all__ = ["check_unit_mistakes", "RADIAN_LIKE_DEG", "METRE_LIKE_LENGTH"]

#: A contact angle below this [deg] reads as radians: pi/2 rad is the largest angle a
#: contact angle can have, and no ball CVT has a disc contact angle of one or two degrees
#: (Table I: 45 deg; the tilt geometry needs tens of degrees, docs/model.md §10).
RADIAN_LIKE_DEG = math.pi / 2
#: A ball radius or bearing diameter at or above this [m] reads as millimetres given as
#: metres (Table I: r_S = 30 mm; the largest traction drives have balls of a few cm).
METRE_LIKE_LENGTH = 1.0

_ANGLES = ("theta0_deg", "theta2_deg")
_LENGTHS = {
    "roller_radius": "ball radius",
    "roller_bearing_diameter": "ball axle bearing diameter",
    "idler_bearing_diameter": "idler bearing diameter",
}


def check_unit_mistakes(design) -> None:
    """Warn of a design angle given in radians; refuse a length given in millimetres.

    Parameters
    ----------
    design : Design
        The design (`ballcvt.params.models.Design`), its fields already in range.

    Raises
    ------
    InputError
        Naming the length field, its value and the value likely meant.

    Warns
    -----
    UnitHintWarning
        Naming the angle field, its value and the value likely meant.
    """
    for name in _ANGLES:
        value = float(getattr(design, name))
        if 0.0 < value < RADIAN_LIKE_DEG:
            warnings.warn(
                f"{name} = {value:g} deg looks like radians: did you mean "
                f"{math.degrees(value):.1f} deg?",
                UnitHintWarning,
                stacklevel=2,
            )
    for name, what in _LENGTHS.items():
        value = float(getattr(design, name))
        if value >= METRE_LIKE_LENGTH:
            raise InputError(
                name,
                value,
                f"< {METRE_LIKE_LENGTH:g} m",
                message=f"{name} = {value:g}: a {value:g} m {what}: mm given as m? "
                f"(did you mean {value / 1000:g} m; allowed < {METRE_LIKE_LENGTH:g} m)",
            )
