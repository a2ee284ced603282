"""Rolling-contact fatigue life (docs/life.md): the subsurface stress, the life of a
rolling track by a registered life model, ISO 281 bearing ratings, and the rules that
combine lives (Weibull series systems, Miner's rule).

Pure functions, SI units, NumPy broadcasting. The model layer: imports only
`ballcvt.params`, the model layer and the leaves.
"""

from ...registry import LIFE_MODELS
from .base import LifeModel, TrackContact, track_contact
from .calibration import (
    BEARING_6206,
    RATING_6206,
    BallBearing,
    ball_bearing_l10,
    calibrate_constants,
)
from .combine import miner_damage, miner_life, system_l10
from .contact import contact_l10, life_model
from .lundberg_palmgren import fatigue_limit_l10, lp_life, lundberg_palmgren_l10
from .rating import a_iso, bearing_l10, deep_groove_rating
from .stress import orthogonal_shear, peak_pressure
from .zaretsky import zaretsky_l10

__all__ = [
    "LIFE_MODELS",
    "LifeModel",
    "TrackContact",
    "track_contact",
    "contact_l10",
    "life_model",
    "orthogonal_shear",
    "peak_pressure",
    "lp_life",
    "lundberg_palmgren_l10",
    "fatigue_limit_l10",
    "zaretsky_l10",
    "bearing_l10",
    "a_iso",
    "deep_groove_rating",
    "system_l10",
    "miner_damage",
    "miner_life",
    "BallBearing",
    "BEARING_6206",
    "RATING_6206",
    "ball_bearing_l10",
    "calibrate_constants",
]
