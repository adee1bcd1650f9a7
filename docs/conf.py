"""Sphinx configuration of the documentation site (``make docs``; ``make docs-check``).

The user guide is the Markdown in this folder (MyST), the API reference is generated from the
docstrings (api.rst; their NumPy-style sections by _ext/docstring_sections.py), the gallery runs
the scripts of ``examples/`` (sphinx-gallery; ``-D plot_gallery=0`` shows them without running),
the C++ reference renders the installed headers (_ext/cpp_headers.py), and equations.md maps the
paper's equation numbers to the code. Built with ``-W --keep-going``: any warning fails the build.
"""

from __future__ import annotations

import sys
from pathlib import Path

import lidar_overlap

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(DOCS / "_ext"))

project = "lidar_overlap"
author = "the lidar_overlap authors"
copyright = "the lidar_overlap authors, BSD-3-Clause"
release = lidar_overlap.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx_gallery.gen_gallery",
    "cpp_headers",
    "api_coverage",
    "docstring_sections",
    "gallery_pages",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = [
    "_build",
    "_templates",
    "gallery_header.rst",
    "gallery/*.ipynb",
    "gallery/*.py",
    "gallery/*.zip",
]
templates_path = ["_templates"]
# Anchors on the guide's headings, so that a page can link to a section of another.
myst_heading_anchors = 3

# API reference: one page per public name, members documented from their docstrings.
autosummary_generate = True
autosummary_imported_members = True
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_format = "short"


def _gallery_sources() -> Path:
    """A scratch folder of links to the scripts of examples/ and the gallery's header.

    sphinx-gallery runs each script in its own folder and takes any subfolder with a README as a
    section: the scripts run here, so the PNG files they write land outside the source tree, and
    examples/data and examples/scenarios stay out of the gallery. A script that reads its data
    finds it through ``Path(__file__).resolve()``, the link's target.
    """
    staging = ROOT / "build" / "docs" / "examples"
    staging.mkdir(parents=True, exist_ok=True)
    for stale in staging.iterdir():
        if stale.is_symlink() or stale.suffix == ".png":
            stale.unlink()
    (staging / "GALLERY_HEADER.rst").symlink_to(DOCS / "gallery_header.rst")
    for script in sorted((ROOT / "examples").glob("*.py")):
        (staging / script.name).symlink_to(script)
    return staging


# Gallery: every script of examples/ run in the scratch folder, the PNG files it writes shown below
# it, with what it prints. The scripts use matplotlib's Agg backend and save their own figures.
sphinx_gallery_conf = {
    "examples_dirs": str(_gallery_sources()),
    "gallery_dirs": "gallery",
    "filename_pattern": r"\.py$",
    "ignore_pattern": r"__init__\.py",
    "image_scrapers": ("gallery_pages.written_pngs",),
    "reset_argv": "gallery_pages.run_as_script",
    "download_all_examples": False,
    "write_computation_times": True,
    "min_reported_time": 0,
    "remove_config_comments": True,
    "show_memory": False,
    "abort_on_example_error": True,
}

html_theme = "furo"
html_title = f"lidar_overlap {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
