"""The interfaces layer: the interactive explorer in the browser (Bokeh server, ``ballcvt explore-ui``)."""

from .app import MAP_GRID, SLIDERS, make_document, serve

__all__ = ["MAP_GRID", "SLIDERS", "make_document", "serve"]
