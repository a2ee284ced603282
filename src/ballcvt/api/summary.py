"""`SummaryMethods`: how a `Variator` shows itself (text and notebook HTML)."""

from __future__ import annotations

from typing import Any

from .._display import html_summary, text_summary
from ..params.models import Design, Fluid

__all__ = ["SummaryMethods"]


class SummaryMethods:
    """The summary of a `Variator` (its design, fluid, architecture, range and law); its
    fields are declared here for typing."""

    design: Design
    fluid: Fluid
    architecture: str
    options: Any
    ratio_range: Any

    def _summary(self) -> tuple[str, list]:
        lo, hi = self.ratio_range
        d, q = self.design, self.options.quadrature
        rows = [
            ("design", d.name, ""),
            ("fluid", self.fluid.name, ""),
            ("architecture", f"{self.architecture} idler", ""),
            ("rollers", f"{d.n_rollers} x r_S {d.roller_radius * 1e3:.4g}", "mm"),
            ("aspect ratio k", d.aspect_ratio, "-"),
            ("contact angles", f"{d.theta0_deg:g} / {d.theta2_deg:g}", "deg"),
            ("ratio range", f"{lo:.3f} - {hi:.3f}", "-"),
            ("traction law", self.fluid.traction_law, ""),
            ("quadrature", f"{q.n_radial} x {q.n_angular}", "nodes"),
        ]
        return "Variator", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())
