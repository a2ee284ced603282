"""Combining lives: strict-series Weibull systems and Miner's rule (docs/life.md §4).

Pure functions, NumPy broadcasting over the last axis.
"""

from __future__ import annotations

import numpy as np

__all__ = ["system_l10", "miner_damage", "miner_life"]


def system_l10(lives, weibull_slope):
    """Life of elements in series (the first failure fails the system), same reliability.

    ``L_sys^-e = sum_i L_i^-e`` (Lundberg and Palmgren 1947; Zaretsky, NASA RP-1154
    Eq. 27), which follows from multiplying the Weibull survivals
    ``S_i = exp(ln(0.9) (N / L_i)^e)`` of elements with one slope ``e``. Two equal
    elements live ``L 2^(-1/e)``.

    Parameters
    ----------
    lives : array_like
        Lives of the elements along the last axis, in one unit (cycles, revolutions,
        hours); ``inf`` for an element that never fails.
    weibull_slope : float
        Weibull slope ``e`` [-] (10/9 for bearing steel).

    Returns
    -------
    ndarray
        System life [unit of ``lives``] (``inf`` if every element lives forever).
    """
    lives = np.asarray(lives, dtype=float)
    with np.errstate(divide="ignore"):
        total = np.sum(lives ** (-float(weibull_slope)), axis=-1)
        return total ** (-1.0 / float(weibull_slope))


def miner_damage(cycles_per_step, lives_per_step):
    """Palmgren-Miner damage of a load history: ``D = sum_i n_i / L_i``.

    Palmgren (1924), Miner (1945); failure (at the reliability of ``L_i``) when ``D``
    reaches 1.

    Parameters
    ----------
    cycles_per_step : array_like
        Cycles (or revolutions, or hours) ``n_i`` spent at each step, last axis [-].
    lives_per_step : array_like
        Life ``L_i`` at each step's constant load, same unit as ``n_i`` (``inf``: no
        damage).

    Returns
    -------
    ndarray
        Damage ``D`` [-].
    """
    cycles = np.asarray(cycles_per_step, dtype=float)
    with np.errstate(divide="ignore"):
        return np.sum(cycles / np.asarray(lives_per_step, dtype=float), axis=-1)


def miner_life(cycles_per_step, lives_per_step):
    """How many times a load history can be repeated before failure: ``1 / D``.

    With fractions of time (or of cycles) ``f_i`` summing to 1 as ``cycles_per_step``
    this is the life under the mixed history, ``L = 1 / sum_i (f_i / L_i)`` (Harris and
    Kotzalas, Rolling Bearing Analysis, 5th ed., Eq. 11.21), in the unit of ``L_i``.

    Parameters
    ----------
    cycles_per_step, lives_per_step : array_like
        As `miner_damage`.

    Returns
    -------
    ndarray
        Repetitions of the history to failure [-] (``inf`` if it does no damage).
    """
    with np.errstate(divide="ignore"):
        return 1.0 / miner_damage(cycles_per_step, lives_per_step)
