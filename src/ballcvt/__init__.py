"""ballcvt: steady-state performance model of ball-type traction CVTs.

Implements Tomaselli, Bottiglione, Lino, Carbone, "NuVinci drive: modeling and performance
analysis", Mech. Mach. Theory 150 (2020) 103877, with the resolutions of its ambiguities
documented in ``docs/model.md``.

Quick start::

    from ballcvt import Variator
    r = Variator().solve(ratio=1.0, output_torque=40.0, clamp_force=2000.0,
                         input_speed_rpm=2000)
    print(r.eta, r.contacts["output"].creep)
"""

from . import _compat
from ._version import __version__
from .api import Variator
from .errors import BallCVTError, ConvergenceError, InputError, TractionLimitError
from .model.traction.quadrature import REFERENCE, Quadrature
from .params import Design, Fluid, OperatingPoint, drive_to_toml, load_builtin, load_drive
from .results.point import ContactResult, OperatingResult
from .solvers.options import SolverOptions

_compat.install()

__all__ = [
    "__version__",
    "Variator",
    "Design",
    "Fluid",
    "OperatingPoint",
    "load_builtin",
    "load_drive",
    "drive_to_toml",
    "OperatingResult",
    "ContactResult",
    "SolverOptions",
    "Quadrature",
    "REFERENCE",
    "BallCVTError",
    "InputError",
    "TractionLimitError",
    "ConvergenceError",
]
