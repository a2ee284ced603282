"""`FatigueMaterial`: the rolling-contact fatigue constants of a bearing steel.

The constants of the life models of `ballcvt.model.life` (docs/life.md): the
Lundberg-Palmgren exponents and material constant, Zaretsky's stress-life exponent and
constant, the ISO 281 fatigue-limit contact pressure, and the elastic constants the
calibration used. The numbers live in a cited data file
(``ballcvt/params/data/steel_52100.toml``); every key is required.
"""

from __future__ import annotations

import math
from pathlib import Path

import tomlkit

from ..errors import InputError
from .base import ParameterModel, _f
from .io import _data_text, parse_toml, read_text

__all__ = [
    "FatigueMaterial",
    "BUILTIN_MATERIALS",
    "load_material",
    "parse_material",
    "material_to_toml",
]

#: Named, cited fatigue materials shipped with the package.
BUILTIN_MATERIALS = {"steel_52100": "steel_52100.toml"}


class FatigueMaterial(ParameterModel):
    """Rolling-contact fatigue constants of one material (docs/life.md).

    The Lundberg-Palmgren constant ``lp_constant`` and the Zaretsky constant
    ``zaretsky_constant`` belong to their exponents and to the elastic constants they
    were calibrated with (the ISO 281 rating of a 6206 ball bearing,
    `ballcvt.model.life.calibrate_constants`): change one and recalibrate the others.
    """

    name: str = _f("-", "name of the material and of its sources")
    youngs_modulus: float = _f("Pa", "Young's modulus E of the calibration", gt=0, lt=math.inf)
    poisson_ratio: float = _f("-", "Poisson ratio nu of the calibration", ge=0, lt=0.5)
    stress_exponent: float = _f(
        "-", "Lundberg-Palmgren exponent c of the orthogonal shear stress (31/3)", gt=0, lt=100
    )
    depth_exponent: float = _f(
        "-", "Lundberg-Palmgren exponent h of the depth z0 (7/3)", ge=0, lt=100
    )
    weibull_slope: float = _f("-", "Weibull slope e of the life scatter (10/9)", gt=0, lt=100)
    lp_constant: float = _f(
        "Pa^c m^(3-h)",
        "Lundberg-Palmgren material constant A: L10^e = A z0^(h-1) / (tau0^c a l)",
        gt=0,
        lt=math.inf,
    )
    zaretsky_stress_exponent: float = _f(
        "-",
        "Zaretsky's stress-life exponent n: L10 ~ p0^-n at fixed contact shape (12)",
        gt=0,
        lt=100,
    )
    zaretsky_constant: float = _f(
        "Pa^(n e - 2) m^3",
        "Zaretsky material constant B: L10^e = B / (tau0^(n e - 2) a z0 l)",
        gt=0,
        lt=math.inf,
    )
    fatigue_limit_pressure: float = _f(
        "Pa",
        "ISO 281 fatigue limit as a peak Hertz pressure p_u (1.5 GPa, 52100 steel)",
        ge=0,
        lt=math.inf,
    )

    @property
    def reduced_modulus(self) -> float:
        """Plane-strain modulus ``E' = E / (1 - nu^2)`` of two bodies of this material
        (Hamrock-Brewe's ``E'``) [Pa]."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)

    @classmethod
    def builtin(cls, name: str = "steel_52100") -> FatigueMaterial:
        """The built-in material ``name`` (`BUILTIN_MATERIALS`; default AISI 52100)."""
        return load_material(name)


def load_material(name: str | Path = "steel_52100") -> FatigueMaterial:
    """A built-in material by name (`BUILTIN_MATERIALS`), else a material TOML file.

    Raises
    ------
    InputError
        If the name is unknown and no such file exists, or the file is not a valid
        ``[material]`` table.
    """
    if str(name) in BUILTIN_MATERIALS and not Path(name).exists():
        text = _data_text(BUILTIN_MATERIALS[str(name)])
        return parse_material(text, source=f"built-in material '{name}'")
    if not Path(name).exists():
        raise InputError(
            "material", str(name), "one of " + ", ".join(BUILTIN_MATERIALS) + " or a TOML file"
        )
    return parse_material(read_text(name, "material file"), source=f"material file {name}")


def parse_material(text: str, source: str = "material file") -> FatigueMaterial:
    """Parse and validate the ``[material]`` table of TOML text."""
    data = parse_toml(text, source)
    if not isinstance(data.get("material"), dict):
        raise InputError(
            "material",
            None,
            "a table",
            message=f"{source} is incomplete: table [material] is missing",
        )
    try:
        return FatigueMaterial(**data["material"])
    except InputError as exc:
        raise InputError(
            exc.quantity, exc.value, exc.allowed, message=f"{source}: {exc}"
        ) from None


def material_to_toml(material: FatigueMaterial, header: str = "") -> str:
    """TOML text (a ``[material]`` table) that `parse_material` reads back unchanged.

    ``header`` is written first as comment lines (sources, calibration).
    """
    doc = tomlkit.document()
    for line in header.splitlines():
        doc.add(tomlkit.comment(line))
    table = tomlkit.table()
    for key, value in material.model_dump().items():
        table[key] = value
    doc["material"] = table
    return tomlkit.dumps(doc)
