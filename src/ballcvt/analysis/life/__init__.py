"""Rolling-contact fatigue life of a drive (docs/life.md): every disc, idler and ball track
and every rated support bearing, at a point, over a duty cycle (Miner's rule) and over a
sweep or map. Built on the physics of `ballcvt.model.life`."""

from ..._lazy import lazy_exports

#: Public name -> the submodule that defines it (loaded on first use: `ballcvt._lazy`).
_EXPORTS = {
    "LifeSettings": ".core",
    "LIFE_MODELS": ".core",
    "LifeResult": ".result",
    "ElementLife": ".result",
    "point_life": ".point",
    "cycle_life": ".cycle",
    "sweep_life": ".maps",
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

__all__ = [
    "LifeSettings",
    "LIFE_MODELS",
    "LifeResult",
    "ElementLife",
    "point_life",
    "cycle_life",
    "sweep_life",
]
