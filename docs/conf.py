"""Sphinx configuration of the ballcvt documentation (``sphinx-build -W -b html docs
docs/_build/html``; the README's Documentation section)."""

import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))
os.environ.setdefault("MPLBACKEND", "Agg")

import ballcvt  # noqa: E402

project = "ballcvt"
author = "ballcvt developers"
copyright = "2026, ballcvt developers (BSD 3-Clause)"
release = version = ballcvt.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "sphinxarg.ext",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "_generated", "Thumbs.db", ".DS_Store", "auto_examples/*.ipynb",
                    "auto_examples/*.py", "auto_examples/*.zip", "auto_examples/*.json",
                    "auto_examples/*.md5", "sg_execution_times.rst"]
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]

napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_pydantic_model_show_json = False
default_role = "py:obj"

sys.path.insert(0, str(ROOT / "tools"))
import figcheck  # noqa: E402


sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples" / "gallery"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "abort_on_example_error": True,
    # sphinx-gallery's matplotlib scraper, once tools/figcheck.py passed every figure
    "image_scrapers": (figcheck.CheckedScraper(),),
}

html_theme = "furo"
html_title = f"ballcvt {release}"

# docs/architecture.md shows the package's layers as they are: the diagram and the table
# are drawn from the source's imports at every build (tools/codemap.py), never by hand.
import codemap  # noqa: E402

_GENERATED = Path(__file__).resolve().parent / "_generated"
_GENERATED.mkdir(exist_ok=True)
_graph = codemap.import_graph(codemap.ROOT)
codemap.draw_layers(_graph, _GENERATED / "layers.png")
(_GENERATED / "layers_table.md").write_text(codemap.layer_table(_graph) + "\n")
(_GENERATED / "hygiene.md").write_text(codemap.figures_markdown() + "\n")

# docs/model.md §1's labelled geometry figure, drawn at every build (tools/geometry_figure.py)
import geometry_figure  # noqa: E402

geometry_figure.draw(_GENERATED / "geometry.png")
