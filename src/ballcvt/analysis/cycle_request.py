"""How a duty cycle is run (`CycleRequest`), checked against the cycle it runs on.

Which option each strategy uses (docs/cycles.md):

| option | ``target-input-speed`` | ``max-efficiency`` | commanded ratio (input side) |
|---|---|---|---|
| ``target_input_speed`` | required | refused | refused |
| ``candidates`` | refused | used (9 by default) | refused |
| ``ratio_range`` | clips the ratio | bounds the search | clips the ratio |

With no strategy an output-side cycle holds ``target_input_speed`` if one is given and
runs ``max-efficiency`` otherwise; an input-side cycle runs ``max-efficiency`` unless its
``ratio`` column commands the ratio. An option the strategy does not use is refused with one
line naming it and the strategy that uses it, never ignored.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from ..errors import InputError
from ..model.kinematics import ratio_range as usable_ratio_range
from .cycle_files import STRATEGIES, Cycle

__all__ = ["CycleRequest", "COMMANDED", "DEFAULT_CANDIDATES", "allowed_ratios"]

#: What `CycleRequest.resolve` names the run of an input-side cycle with a ``ratio`` column.
COMMANDED = "commanded ratio"
#: Ratios tried per step by ``max-efficiency`` when ``candidates`` is not given.
DEFAULT_CANDIDATES = 9


@dataclass(frozen=True)
class CycleRequest:
    """How a duty cycle is run (`ballcvt.analysis.cycles.run_cycle`).

    Attributes
    ----------
    strategy : {"target-input-speed", "max-efficiency"}, optional
        How the ratio is chosen (output-side cycles, and input-side ones without a
        ``ratio`` column). None: ``target-input-speed`` when ``target_input_speed`` is
        given, else ``max-efficiency``.
    target_input_speed : float, optional
        Input speed held by ``target-input-speed`` [rad/s] (that strategy only).
    clamp_force, clamp_law
        As in `Variator.solve` (constant force [N], ``cam``, ``optimal`` or a law object).
    candidates : int, optional
        Ratios tried per step by ``max-efficiency`` (3-101; `DEFAULT_CANDIDATES` when None;
        that strategy only).
    ratio_range : (float, float), optional
        Ratios any strategy may use [-], within the usable range (its default): the
        ``max-efficiency`` search stays within it, a held or commanded ratio outside it runs
        at its end (flagged ``ratio_limited``).
    progress : bool, optional
        Progress bar (default: when stderr is a terminal).
    workers : int
        Processes to solve the steps on (1-64; the same results, to round-off).
    """

    strategy: str | None = None
    target_input_speed: float | None = None
    clamp_force: float | None = None
    clamp_law: Any = None
    candidates: int | None = None
    ratio_range: Any = None
    progress: bool | None = None
    workers: int = 1

    def check(self) -> None:
        """Refuse settings out of range (one `InputError` naming the setting)."""
        if self.strategy is not None and self.strategy not in STRATEGIES:
            raise InputError("strategy", self.strategy, "one of: " + ", ".join(STRATEGIES))
        if self.candidates is not None and not 3 <= int(self.candidates) <= 101:
            raise InputError("candidates", self.candidates, "3-101")
        if not 1 <= int(self.workers) <= 64:
            raise InputError("workers", self.workers, "1-64")

    def resolve(self, cycle: Cycle) -> CycleRequest:
        """This request with its strategy (or `COMMANDED`) and candidates decided for
        ``cycle``; an option the strategy does not use is refused (`InputError`)."""
        self.check()
        if cycle.kind == "input" and cycle.ratio is not None:
            if self.strategy is not None:
                raise InputError(
                    "strategy", self.strategy, "none: the cycle's ratio column commands the ratio"
                )
            strategy = COMMANDED
        elif self.strategy is not None:
            strategy = self.strategy
        elif cycle.kind == "output" and self.target_input_speed is not None:
            strategy = "target-input-speed"
        else:
            strategy = "max-efficiency"
        if strategy == "target-input-speed":
            _check_target(self, cycle)
        elif self.target_input_speed is not None:
            raise InputError(
                "target_input_speed",
                self.target_input_speed,
                f"not given: it is held by the target-input-speed strategy only ({strategy} "
                + ("picks the input speed)" if cycle.kind == "output" else "uses the cycle's)"),
            )
        if strategy != "max-efficiency" and self.candidates is not None:
            raise InputError(
                "candidates",
                self.candidates,
                f"not given: the max-efficiency strategy uses it, not {strategy}",
            )
        return replace(self, strategy=strategy, candidates=self.candidates or DEFAULT_CANDIDATES)


def _check_target(s: CycleRequest, cycle: Cycle) -> None:
    """``target-input-speed`` needs an output-side cycle and a positive target speed."""
    if cycle.kind == "input":
        raise InputError(
            "strategy",
            s.strategy,
            "max-efficiency (an input-side cycle without a ratio column fixes the input "
            "speed already)",
        )
    if s.target_input_speed is None:
        raise InputError(
            "target_input_speed",
            None,
            "> 0 rad/s",
            message="target_input_speed (--target-speed [rpm]) is required by the "
            "target-input-speed strategy; without it, max-efficiency picks the ratio",
        )
    if not s.target_input_speed > 0:
        raise InputError("target_input_speed", s.target_input_speed, "> 0 rad/s")


def allowed_ratios(design, s: CycleRequest) -> tuple[float, float]:
    """The ratios the run may use [-]: ``ratio_range``, within the design's usable range
    (that range when None)."""
    lo, hi = usable_ratio_range(design)
    r_lo, r_hi = (lo, hi) if s.ratio_range is None else map(float, s.ratio_range)
    if not lo <= r_lo < r_hi <= hi:
        raise InputError(
            "ratio_range",
            f"{r_lo:g} {r_hi:g}",
            f"MIN < MAX within the usable range {lo:.4g}-{hi:.4g}",
        )
    return r_lo, r_hi
