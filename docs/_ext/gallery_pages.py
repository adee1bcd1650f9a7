"""The gallery's pages: the PNG files an example writes are its pictures, its file name the title.

The examples save their own figures (``fig.savefig("name.png")``, as ``make demo`` keeps them) and
may close them, so matplotlib's open figures are not a reliable record. sphinx-gallery runs each
script in its own scratch folder (conf.py); after each code block :func:`written_pngs` takes the PNG
files that appeared there, in the order they were written, into the gallery's image folder.
:func:`run_as_script` runs each script as ``python script.py`` would, ``__file__`` included.

The scripts open with plain prose, not a reStructuredText title; each page is titled with the
script's file name, the name ``make demo`` and the README use.
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path
from typing import Any

from sphinx.application import Sphinx
from sphinx_gallery.scrapers import figure_rst

GALLERY = "gallery"


def written_pngs(block: Any, block_vars: dict[str, Any], gallery_conf: dict[str, Any]) -> str:
    """Move the PNG files written into the working folder to the gallery's image paths."""
    written = sorted(Path(os.getcwd()).glob("*.png"), key=lambda p: (p.stat().st_mtime, p.name))
    images = []
    for png, image_path in zip(written, block_vars["image_path_iterator"]):
        shutil.move(png, image_path)
        images.append(image_path)
    return figure_rst(images, gallery_conf["src_dir"])


def run_as_script(gallery_conf: dict[str, Any], script_vars: dict[str, Any]) -> list[str]:
    """sphinx-gallery's ``reset_argv`` hook, called just before a script runs: no arguments, and
    ``__file__`` set as ``python script.py`` sets it (sphinx-gallery leaves it out), so that a
    script that finds its data beside itself (``Path(__file__).resolve().parent``) runs here too."""
    script_vars["example_globals"]["__file__"] = script_vars["src_file"]
    return []


def _title(app: Sphinx, docname: str, source: list[str]) -> None:
    if not docname.startswith(GALLERY + "/") or docname == GALLERY + "/index":
        return
    script = docname.split("/", 1)[1] + ".py"
    label = re.compile(rf"^\.\. _sphx_glr_{GALLERY}_{re.escape(script)}:\n", re.MULTILINE)
    source[0] = label.sub(lambda m: f"{m.group(0)}\n{script}\n{'=' * len(script)}\n", source[0], 1)


def setup(app: Sphinx) -> dict[str, object]:
    app.connect("source-read", _title)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
