"""The oil's temperature in `Variator.solve` and `Variator.run_cycle` (docs/model.md §15).

``oil_temperature="balance"`` solves the housing's steady heat balance
``P_loss(T) = h A (T - T_amb)``: each evaluation of ``P_loss(T)`` is a full operating point
with the fluid at ``T`` (`ballcvt.model.oil.fluid_at`). The root is bracketed from the
ambient upwards by fixed-point steps ``T <- T_amb + P_loss(T) / (h A)`` and then found by
Brent's method to `BALANCE_TOL` (each step that does not cross is followed by the secant's
step, 10 % past its root: near the capacity the losses rise with the temperature nearly as
fast as the heat rejected and the fixed point crawls); if the losses still exceed what
the housing rejects at `MAX_OIL_TEMPERATURE` there is no balance (a runaway) and the point
is refused.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from scipy.optimize import brentq

from ..analysis.oil_sweep import STRETCH_MAX, STRETCH_RTOL, inward_trial, outward_trial
from ..errors import BallCVTError, ConvergenceError, InputError, NoEquilibriumError
from ..model.modes import resolve_mode
from ..model.oil import C_TO_K, MAX_OIL_TEMPERATURE, fluid_at, steady_temperature
from ..params.drive_models import with_oil_model
from ..results.planetary import PlanetaryResult
from ..solvers.refusal import CREEP_RTOL

__all__ = [
    "solve_with_oil",
    "cycle_with_oil",
    "oil_choice",
    "path_choice",
    "at_temperature",
    "sweep_with_oil",
    "limit_with_oil",
    "with_oil_temperature",
    "thermal_of",
    "MAX_OIL_TEMPERATURE",
    "BALANCE_TOL",
]

#: Tolerance of the balance's temperature [K].
BALANCE_TOL = 1e-4
#: Fixed-point steps to bracket the balance before refusing.
MAX_BRACKET_STEPS = 30
#: How far past the secant's root the bracket reaches after a fixed-point step that did
#: not cross (the losses rising with the temperature, near the capacity, slow the fixed
#: point down: it converges as (dP/dT) / (h A) per step) [-].
SECANT_REACH = 1.1


def drive_choice(design, value: Any, cycle: bool = False, mode=None) -> str | float:
    """The oil-temperature model of a call: ``value`` if given, else the drive file's
    (``[models] oil_temperature``, `ballcvt.params.drive_models`), else ``"fixed"``.

    A drive that names ``"balance"`` runs a cycle's steps through the housing's lumped
    transient (``"transient"``, which needs ``thermal_mass``) and a point through the
    steady balance; without a thermal mass its cycles run at the fixed temperature. In a
    planetary ``mode`` (`ballcvt.model.modes`) the drive's choice is not taken: its maps,
    limits and cycles run the fluid as given, and so do its points unless asked.
    """
    if value is not None:
        return value
    if mode is not None and not resolve_mode(mode).is_default:
        return "fixed"
    models = getattr(design, "models", None)
    named = getattr(models, "oil_temperature", None) or "fixed"
    if named == "balance" and cycle:
        thermal = design.thermal
        return "transient" if thermal is not None and thermal.thermal_mass else "fixed"
    return named


def oil_choice(value: Any, models: tuple[str, ...]) -> str | float:
    """``value`` as one of ``models`` or a temperature [K]; `InputError` otherwise."""
    if isinstance(value, str) and value in models:
        return value
    if isinstance(value, int | float) and not isinstance(value, bool):
        if 150.0 < float(value) < 700.0:
            return float(value)
    raise InputError("oil_temperature", value, " or ".join(models) + " or a temperature 150-700 K")


def thermal_of(design):
    """The design's ``[design.thermal]``; `InputError` when it has none."""
    if design.thermal is None:
        raise InputError(
            "design.thermal",
            None,
            "a [design.thermal] table (housing_area, heat_transfer_coefficient, "
            "ambient_temperature) for the oil's heat balance",
        )
    return design.thermal


def _loss(result) -> float:
    """Total power loss of a point [W]."""
    return result.loss if isinstance(result, PlanetaryResult) else result.losses["total"]


def _tag(result, model: str, iterations: int):
    """``result`` with how its oil temperature was set."""
    if isinstance(result, PlanetaryResult):
        rel = replace(result.relative, oil_model=model, thermal_iterations=iterations)
        return replace(result, relative=rel)
    return replace(result, oil_model=model, thermal_iterations=iterations)


def solve_with_oil(variator, settings, ratio: float, output_torque: float, point: dict):
    """`Variator.solve` under ``settings.oil_temperature`` other than ``"fixed"``.

    Parameters
    ----------
    variator : Variator
        The drive (its fluid as given, at its reference temperature).
    settings : SolveSettings
        With ``oil_temperature`` ``"balance"`` or a temperature [K].
    ratio, output_torque : float
        As in `Variator.solve` [-], [N m].
    point : dict
        The other keywords of `Variator.solve` (clamping and speed).

    Returns
    -------
    OperatingResult or PlanetaryResult
        Solved with the fluid at the oil temperature (``oil_temperature`` [K],
        ``oil_model``, ``thermal_iterations``).

    Raises
    ------
    InputError
        No ``[design.thermal]``, a fluid without temperature data, or no balance below
        `MAX_OIL_TEMPERATURE` (the losses outgrow the housing's heat rejection).
    """
    choice = oil_choice(settings.oil_temperature, ("fixed", "balance"))
    fixed = replace(settings, oil_temperature="fixed")
    trial = replace(fixed, check_capacity=False)

    def at(temperature: float, how=trial):
        drive = replace(variator, fluid=fluid_at(variator.fluid, temperature))
        try:
            return drive.solve(ratio, output_torque, settings=how, **point)
        except ConvergenceError:  # no equilibrium: refused as `Variator.solve` refuses
            if how is fixed or not settings.check_capacity:
                raise
            return drive.solve(ratio, output_torque, settings=fixed, **point)

    if isinstance(choice, float):
        return _tag(at(choice, fixed), "given", 0)
    thermal = thermal_of(variator.design)
    temperature, result, evaluations = balance(at, thermal)
    if settings.check_capacity:  # judged at its own balance, not at the trial temperatures
        result = at(temperature, fixed)
    return _tag(result, "balance", evaluations)


def balance(at, thermal) -> tuple[float, Any, int]:
    """``(T, result at T, points solved)`` of ``P_loss(T) = h A (T - T_amb)``.

    ``at(T)`` solves the point with the fluid at ``T`` [K]; ``thermal`` is the design's
    `ballcvt.params.thermal.ThermalModel`.
    """
    solved: dict[float, Any] = {}

    def excess(temperature: float) -> float:
        """Loss minus heat rejected at ``temperature`` [W]."""
        if temperature not in solved:
            solved[temperature] = at(temperature)
        rejected = thermal.conductance * (temperature - thermal.ambient_temperature)
        return _loss(solved[temperature]) - rejected

    lo = thermal.ambient_temperature
    if excess(lo) <= 0.0:  # no loss: the oil is at the ambient
        return lo, solved[lo], len(solved)
    for _ in range(MAX_BRACKET_STEPS):
        ambient, conductance = thermal.ambient_temperature, thermal.conductance
        hi = min(steady_temperature(_loss(solved[lo]), conductance, ambient), MAX_OIL_TEMPERATURE)
        e_lo, e_hi = excess(lo), excess(hi)
        if 0.0 < e_hi < e_lo and hi - lo > BALANCE_TOL:  # the secant, a little past its root
            ahead = hi + SECANT_REACH * e_hi * (hi - lo) / (e_lo - e_hi)
            lo, hi = hi, min(ahead, MAX_OIL_TEMPERATURE)
        if excess(hi) <= 0.0:
            break
        if hi >= MAX_OIL_TEMPERATURE:
            raise runaway(_loss(solved[hi]), thermal)
        if hi - lo <= BALANCE_TOL:  # the fixed point converged from below
            return hi, solved[hi], len(solved)
        lo = hi
    else:
        raise runaway(_loss(solved[lo]), thermal)
    root = brentq(excess, lo, hi, xtol=BALANCE_TOL)
    excess(root)
    return root, solved[root], len(solved)


def runaway(loss: float, thermal) -> InputError:
    """The refusal of a point with no heat balance below `MAX_OIL_TEMPERATURE`."""
    t_max = MAX_OIL_TEMPERATURE - C_TO_K
    return InputError(
        "oil_temperature",
        "balance",
        "a point whose losses the housing can reject",
        message=f"no oil heat balance below {t_max:.0f} C: the losses ({loss:.4g} W at "
        f"{t_max:.0f} C) exceed what the housing rejects, h A (T - T_amb) = "
        f"{thermal.conductance:.4g} W/K x {t_max - (thermal.ambient_temperature - C_TO_K):.0f} K "
        "(a thermal runaway: more housing area or cooling)",
    )


def cycle_with_oil(variator, cycle, settings, clamp: dict, mode):
    """`Variator.run_cycle` under ``settings.oil_temperature`` other than ``"fixed"``:
    ``"transient"`` (the housing's lumped transient,
    `ballcvt.analysis.oil_cycle.run_cycle_with_oil`) or a temperature [K].

    ``clamp`` holds ``clamp_force`` and ``clamp_law`` as given to `Variator.run_cycle`;
    ``mode`` its operating mode (the carrier-held drive only).
    """
    from ..analysis.cycle_request import CycleRequest
    from ..analysis.oil_cycle import OilTransient, run_cycle_with_oil

    choice = oil_choice(settings.oil_temperature, ("fixed", "transient"))
    start = settings.initial_oil_temperature
    if start is not None and choice != "transient":
        raise InputError(
            "initial_oil_temperature", start, "given with oil_temperature 'transient' only"
        )
    if not mode.is_default:
        raise InputError("oil_temperature", choice, "fixed in a planetary mode (not modelled)")
    request = CycleRequest(
        strategy=settings.strategy,
        target_input_speed=settings.target(),
        candidates=settings.candidates,
        ratio_range=settings.ratio_range,
        progress=settings.progress,
        workers=settings.workers,
        **clamp,
    )
    if isinstance(choice, float):
        oil = OilTransient(thermal=variator.design.thermal, fixed_temperature=choice)
        return run_cycle_with_oil(variator, cycle, request, oil)
    thermal = thermal_of(variator.design)
    if thermal.thermal_mass is None:
        raise InputError(
            "design.thermal.thermal_mass", None, "> 0 J/K (the oil's transient over a cycle)"
        )
    if start is not None and not 150.0 < float(start) < MAX_OIL_TEMPERATURE:
        raise InputError("initial_oil_temperature", start, f"150 to {MAX_OIL_TEMPERATURE:g} K")
    oil = OilTransient(thermal=thermal, initial_temperature=start)
    return run_cycle_with_oil(variator, cycle, request, oil)


def at_temperature(variator, temperature: float):
    """``variator`` with its fluid at ``temperature`` [K] and its oil model ``"fixed"``
    (the paths run on it as on any drive)."""
    design = with_oil_model(variator.design, "fixed")
    return replace(variator, design=design, fluid=fluid_at(variator.fluid, temperature))


def path_choice(variator, value: Any = None) -> str | float:
    """The oil-temperature model of a sweep, map, table or limit: ``value``, else the
    drive file's (`drive_choice`), as ``"fixed"``, ``"balance"`` or a temperature [K]."""
    return oil_choice(drive_choice(variator.design, value), ("fixed", "balance"))


def sweep_with_oil(variator, choice: str | float, request):
    """`Variator.sweep` of ``request`` (`ballcvt.analysis.sweeps.grid.SweepRequest`) under
    the oil model ``choice``: ``"fixed"`` the fluid as given, a temperature [K] the fluid
    there, ``"balance"`` each point at its own heat balance
    (`ballcvt.analysis.oil_grid.balanced_sweep`). Not ``"fixed"``: the dataset has
    ``oil_temperature`` [K] at each point and the attribute ``oil_model``."""
    from ..analysis.oil_grid import balanced_sweep
    from ..analysis.sweeps.grid import sweep

    if choice == "fixed":
        return sweep(variator.design, variator.fluid, request)
    if choice == "balance":
        return balanced_sweep(
            variator.design, variator.fluid, thermal_of(variator.design), request
        )
    ds = sweep(variator.design, fluid_at(variator.fluid, float(choice)), request)
    ds["oil_temperature"] = ds["status"].astype(float) * 0.0 + float(choice)
    ds["oil_temperature"].attrs.update(long_name="bulk oil temperature (given)", units="K")
    ds.attrs["oil_model"] = "given"
    return ds


class _Idle:
    """The stand-in of a limit point where no torque is admissible: nothing to reject."""

    losses = {"total": 0.0}


def limit_with_oil(variator, choice: str | float, ratio: float, point: dict, whole: bool = True):
    """``(capacity, oil temperature [K])`` of `Variator.capacity` at the oil temperature
    its limit point produces: the largest admissible torque solved (`LIMIT_SHY` below it)
    with the fluid at ``T``, whose loss balances ``h A (T - T_amb)`` (`balance`); under a
    given temperature, the capacity there. A limit point whose losses the housing cannot
    reject below `MAX_OIL_TEMPERATURE` takes the capacity at that temperature (the
    hottest oil modelled; `Variator.solve` refuses such a point as a thermal runaway).
    Under the balance the ends of that capacity are then moved to where `Variator.solve`,
    each torque at its own balance, switches between carrying and refusing
    (`_balanced_ends`).

    ``point`` holds the keywords of `Variator.capacity` (clamping, speeds, creep limit);
    with ``whole`` False the capacity is only `Variator.limit_torque`'s largest torque [N m]
    (without the intervals' constraints: cheaper).
    """
    from ..analysis.oil_sweep import LIMIT_SHY

    found: dict[float, Any] = {}
    keys = ("clamp_force", "clamp_law", "input_speed", "input_speed_rpm")
    solve_point = {k: point[k] for k in keys if k in point}

    def at(temperature: float):
        drive = at_temperature(variator, temperature)
        cap = drive.capacity(ratio, **point) if whole else drive.limit_torque(ratio, **point)
        found[temperature] = cap
        top = cap if not whole else cap.intervals[-1][1] if cap.intervals else float("nan")
        if not top >= 0.0:  # (no admissible torque)
            return _Idle()
        top = top * (1.0 - LIMIT_SHY)
        return drive.solve(ratio, top, check_capacity=False, **solve_point)

    if choice != "balance":
        at(float(choice))
        return found[float(choice)], float(choice)
    try:
        temperature = balance(at, thermal_of(variator.design))[0]
    except InputError:
        if MAX_OIL_TEMPERATURE not in found:
            raise
        temperature = MAX_OIL_TEMPERATURE  # a runaway: the limit with the hottest oil
    return _balanced_ends(variator, ratio, point, found[temperature]), temperature


def _balanced_ends(variator, ratio: float, point: dict, cap):
    """``cap`` with every end of its intervals moved to where `Variator.solve` under the
    balance switches between carrying the torque and refusing it, to `STRETCH_RTOL`.

    The capacity found at the balance temperature ``T*`` of its limit point is that of
    the fluid at ``T*``; every other torque ``t`` runs at its own balance ``T(t)``, and the
    oil reached from the ambient is the first root of the balance. Where the losses change
    with the temperature the ends move: a cam's lower interval ends at a colder oil than
    its top (more viscous, more drag to carry), a cam's pressure-bound top moves with the
    efficiency (the input torque sets the force), and under a law with a fold (the thermal
    law) the balance temperature climbs steeply near the fold, so that torques above the
    fixed point ``t = L(T(t))`` may still be carried (``L'(T) T'(t) > 1``). Each end is
    found from the fixed point's by steps growing fourfold from `STRETCH_RTOL` (outwards
    as far as the neighbouring interval, or `STRETCH_MAX` above the largest torque;
    inwards as far as the interval's other end), then bisection, each a balanced solve judged as `Variator.solve` judges
    a point (converged, every creep within the limit, under a torque-following law the
    peak pressure within ``max_pressure``); intervals that close up are dropped, and
    neighbours that meet are joined.
    """
    keys = ("clamp_force", "clamp_law", "input_speed", "input_speed_rpm")
    kw = {k: point[k] for k in keys if k in point}
    c_lim = point.get("creep_limit") or variator.design.creep_limit
    p_lim = variator.design.max_pressure

    refused: dict[float, str] = {}  # torque -> what bounds the capacity there

    def carries(torque: float) -> bool:
        try:
            r = variator.solve(ratio, torque, check_capacity=False, **kw)
        except BallCVTError as exc:
            runaway = isinstance(exc, InputError) and "heat balance" in str(exc)
            refused[torque] = "oil heat balance (runaway)" if runaway else "no equilibrium"
            return False
        name, c = max(r.contacts.items(), key=lambda nc: abs(nc[1].creep))
        if abs(c.creep) > c_lim * (1.0 + CREEP_RTOL):
            refused[torque] = f"creep ({name} contact)"
            return False
        follows = r.clamp_law not in ("constant", "optimal")
        if follows and max(c.p_max for c in r.contacts.values()) > p_lim * (1.0 + 1e-9):
            refused[torque] = f"pressure (max_pressure {p_lim / 1e9:g} GPa)"
            return False
        return True

    def moved(end, stop, reach, label):
        """The end found from ``end`` and what bounds the capacity there."""
        got = _flip(carries, end, stop, reach)
        if got is None:
            return None, label
        inside, outside = got
        return inside, (label if outside is None else refused.get(outside, label))

    if not hasattr(cap, "intervals"):
        if not cap > 0.0:
            return cap
        top = moved(cap, 0.0, cap * (1.0 + STRETCH_MAX), "")[0]
        if top is not None:
            return top
        # carried nowhere at its own balance down to the smallest torque tried (harden
        # task 2720:23: the oil runs away at every torque, and the 150 C oil's capacity
        # was reported): zero torque decides, refused as `Variator.solve` refuses it
        variator.solve(ratio, 0.0, **kw)
        return 0.0 if carries(0.0) else _no_balanced_torque(ratio, refused.get(0.0))
    kept: list = []
    ends = [iv[0] for iv in cap.intervals[1:]] + [cap.largest * (1.0 + STRETCH_MAX)]
    for ((lo, hi), why), nxt in zip(zip(cap.intervals, cap.constraints), ends):
        below = kept[-1][0][1] if kept else 0.0
        why_lo, why_hi = why
        if lo > 0.0:
            lo, why_lo = moved(lo, hi, below, why_lo)
        if hi > 0.0 and lo is not None:
            hi, why_hi = moved(hi, lo, nxt, why_hi)
        if lo is None or hi is None or not lo < hi:
            continue
        if kept and lo <= kept[-1][0][1]:  # met its neighbour: one interval
            (lo, _), (why_lo, _) = kept.pop()
        kept.append(((lo, hi), (why_lo, why_hi)))
    return replace(
        cap,
        intervals=tuple(k[0] for k in kept),
        constraints=tuple(tuple(k[1]) for k in kept),
    )


def _no_balanced_torque(ratio: float, why: str | None):
    """Raise: no output torque is carried at its own oil balance (``why``: what refuses
    zero torque)."""
    raise NoEquilibriumError(
        f"no admissible equilibrium at any output torque with the oil at its own heat "
        f"balance (ratio {ratio:g}): zero torque is refused ({why or 'creep'})",
        {"ratio": f"ratio {ratio:g}"},
    )


def _flip(carries, end: float, stop: float, reach: float):
    """``(inside, outside)``: the torques on either side of where ``carries`` flips
    nearest ``end``, within `STRETCH_RTOL` relative, ``inside`` carried: searched
    outwards as far as ``reach`` where ``end`` is carried (``(reach, None)`` if ``reach``
    is), else inwards as far as ``stop``, the interval's other end
    (`ballcvt.analysis.oil_sweep.outward_trial`, `inward_trial`: steps growing fourfold
    from `STRETCH_RTOL` of ``end``), then bisection. None where nothing before ``stop``
    is carried."""
    inside, outside = None, None
    if carries(end):  # the flip lies further out, before ``reach``
        inside, k = end, 0
        while outside is None:
            trial = float(outward_trial(end, reach, k))
            if trial == reach:
                if carries(reach):
                    return reach, None
                outside = reach
                break
            inside, outside = (trial, None) if carries(trial) else (inside, trial)
            k += 1
    else:  # the flip lies inside, before ``stop``
        outside, k = end, 0
        while inside is None:
            trial = float(inward_trial(end, stop, k))
            if trial != trial:  # (NaN: past the last trial) nothing carried
                return None
            inside, outside = (trial, outside) if carries(trial) else (None, trial)
            k += 1
    while abs(outside - inside) > STRETCH_RTOL * abs(inside):
        mid = 0.5 * (inside + outside)
        inside, outside = (mid, outside) if carries(mid) else (inside, mid)
    return inside, outside


def with_oil_temperature(variator, value: Any):
    """``variator`` computed under the oil model ``value`` on every path: ``"fixed"`` or
    ``"balance"`` (its ``[models] oil_temperature``), or a temperature [K] (the fluid
    there, the model ``"fixed"``); itself for None (the drive file's own choice)."""
    if value is None:
        return variator
    choice = oil_choice(value, ("fixed", "balance"))
    if isinstance(choice, float):
        return at_temperature(variator, choice)
    return replace(variator, design=with_oil_model(variator.design, choice))
