"""The docstrings' NumPy-style sections, rendered as the project writes them.

The package's docstrings head their sections NumPy's way (``Parameters`` over a line of dashes) but
write each entry as ``name : what it is, with units``, the description starting on the name's line,
and may end a section with plain prose. numpydoc and napoleon read the text after the colon as a
type (napoleon puts the description's first line in the type and the rest under the name), so this
turns each section into a rubric and each entry into a definition-list item, its text as written.
"""

from __future__ import annotations

import re
from typing import Any

from sphinx.application import Sphinx

SECTIONS = ("Parameters", "Returns", "Attributes", "Raises", "Yields", "Other Parameters")
# "name : text", "a, b : text" or "name :" (the text on the next, indented lines)
_ENTRY = re.compile(r"^([*A-Za-z_][\w*.,() ]*?)\s+:(?:\s+(.*))?$")


def convert(lines: list[str]) -> list[str]:
    """The docstring's lines with its sections as rubrics and definition lists."""
    out: list[str] = []
    in_section = False
    i = 0
    while i < len(lines):
        line = lines[i]
        underline = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() in SECTIONS and re.fullmatch(r"\s*-{3,}\s*", underline):
            if out and out[-1].strip():
                out.append("")
            out += [f".. rubric:: {line.strip()}", ""]
            in_section = True
            i += 2
            continue
        match = _ENTRY.match(line) if in_section else None
        if match:
            if out and out[-1].strip() and not out[-1].startswith(" "):
                out.append("")  # the previous entry's text or a paragraph ends here
            names = match.group(1).replace("*", r"\*")
            out.append(f"**{names}**")
            if match.group(2):
                out.append("    " + match.group(2))
        elif in_section and line.strip() and not line.startswith(" "):
            if out and out[-1].strip():
                out.append("")  # prose after the entries: a paragraph of its own
            in_section = False
            out.append(line)
        else:
            out.append(line)
        i += 1
    return out


def _process(app: Sphinx, what: str, name: str, obj: Any, options: Any, lines: list[str]) -> None:
    lines[:] = convert(lines)


def setup(app: Sphinx) -> dict[str, object]:
    app.connect("autodoc-process-docstring", _process)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
