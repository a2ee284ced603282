"""`Lubrication`: the lubrication model of a drive and its asperity parameters.

The ``[design.lubrication]`` table of a drive file (docs/drive-files.md). Without it a
drive runs the paper's full film (the ``full-film`` model); ``model = "mixed"`` shares the
load between the film and the asperities (docs/model.md §16,
`ballcvt.model.lubrication`). The asperity parameters have defaults: the typical values
named below, so that ``--lubrication mixed`` works on any drive.
"""

from __future__ import annotations

import math

from pydantic import Field, field_validator

from ..registry import LUBRICATION_MODELS
from .base import ParameterModel

__all__ = ["Lubrication", "BOUNDARY_FRICTION", "ASPERITY_DENSITY_PRODUCT", "ASPERITY_SLOPE"]

#: Boundary friction coefficient of lubricated steel asperities: about 0.1 for steel
#: under boundary films of oils and traction fluids (Bowden and Tabor, *The Friction and
#: Lubrication of Solids* (1950); the value used for the asperity friction of the
#: Stribeck-curve predictions of Gelinck and Schipper, Tribol. Int. 33 (2000) 175-181) [-].
BOUNDARY_FRICTION = 0.1
#: ``eta beta sigma``: asperity density times summit radius times roughness, 0.03-0.05 for
#: most engineering surfaces (Greenwood and Williamson, Proc. R. Soc. A 295 (1966) 300) [-].
ASPERITY_DENSITY_PRODUCT = 0.04
#: ``sigma / beta``: roughness over summit radius, 1e-4 to 1e-2 for engineering surfaces
#: (Greenwood and Williamson 1966); 1e-3 as in the mixed-lubrication analyses of
#: Arcoumanis, Ostovar and Mortier, SAE 972924 (1997) [-].
ASPERITY_SLOPE = 1e-3


class Lubrication(ParameterModel):
    """Lubrication model of the contacts and its asperity parameters (docs/model.md §16)."""

    model: str = Field(
        "full-film",
        description="a name in ballcvt.registry.LUBRICATION_MODELS: 'full-film' (the "
        "paper's), 'mixed' (film and asperities share the load) [-]",
        json_schema_extra={"unit": "-"},
    )
    boundary_friction: float = Field(
        BOUNDARY_FRICTION,
        description="boundary friction coefficient mu_b of the asperity-carried load [-]",
        json_schema_extra={"unit": "-"},
        ge=0,
        lt=1,
    )
    asperity_density_product: float = Field(
        ASPERITY_DENSITY_PRODUCT,
        description="eta beta sigma: summit density x summit radius x RMS roughness "
        "(Greenwood and Williamson 1966) [-]",
        json_schema_extra={"unit": "-"},
        gt=0,
        lt=1,
    )
    asperity_slope: float = Field(
        ASPERITY_SLOPE,
        description="sigma / beta: RMS roughness over summit radius (Greenwood and "
        "Williamson 1966) [-]",
        json_schema_extra={"unit": "-"},
        gt=0,
        lt=math.inf,
    )

    @field_validator("model")
    @classmethod
    def _known(cls, name: str) -> str:
        LUBRICATION_MODELS.get(name)  # an InputError listing the models if unknown
        return name
