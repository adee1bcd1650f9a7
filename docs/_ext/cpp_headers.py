"""Sphinx directive ``cpp-headers``: the installed C++ headers as reference pages.

The headers document themselves with plain ``//`` comments above each declaration (and beside each
member), which Doxygen does not read as documentation; rendering them as written keeps one source.
Each header becomes a section: its opening comment as text, then each top-level declaration with the
comment above it as text and the declaration itself, member comments included, as highlighted C++.
Every declared name gets an entry in the general index, and all of it is in the search index.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import directives
from sphinx import addnodes
from sphinx.application import Sphinx
from sphinx.util.docutils import SphinxDirective

#: Folders in the order of the core's layers (docs/architecture.md); the umbrella header first.
FOLDER_ORDER = ("", "core", "geometry", "fourier", "beams", "atmosphere", "pupil")

# Lines that carry no API: include guards, includes, the namespace braces.
_SKIPPED = re.compile(r"^\s*(#pragma once|#include\b|namespace\s+\w+\s*\{|\}\s*//\s*namespace)")
# What a top-level declaration declares, by its first line: (kind, pattern of its name).
_DECLARED = (
    ("type", re.compile(r"^(?:template\s*<[^>]*>\s*)?(?:struct|class|enum class|enum)\s+(\w+)")),
    ("type alias", re.compile(r"^using\s+(\w+)\s*=")),
    ("constant", re.compile(r"^inline\s+constexpr\s+[\w:<>, ]+?\s(\w+)\s*=")),
    (
        "function",
        re.compile(
            r"^(?:inline\s+|static\s+|constexpr\s+|\[\[nodiscard\]\]\s+)*"
            r"[\w:<>,&* ]+?[\s&*](\w+)\s*\("
        ),
    ),
)


@dataclass
class Block:
    """One top-level declaration (``code``) with the comment lines above it (``doc``)."""

    doc: list[str] = field(default_factory=list)
    code: list[str] = field(default_factory=list)

    def declared(self) -> tuple[str, str] | None:
        """(kind, name) of what this block declares at namespace level, if anything."""
        if not self.code:
            return None
        first = self.code[0].strip()
        if first.startswith("template") and len(self.code) > 1:
            first += " " + self.code[1].strip()  # template <...> on a line of its own
        for kind, pattern in _DECLARED:
            match = pattern.match(first)
            if match:
                return kind, match.group(1)
        return None


def _comment_text(line: str) -> str:
    return line.strip()[2:].strip()


def parse_header(text: str) -> tuple[list[str], list[Block]]:
    """Split a header into its opening comment and its top-level blocks.

    Blocks are separated by blank lines at brace depth 0, so a struct with blank lines inside stays
    one block.
    """
    lines = text.splitlines()
    intro: list[str] = []
    i = 0
    while i < len(lines) and lines[i].lstrip().startswith("//"):
        intro.append(_comment_text(lines[i]))
        i += 1
    blocks: list[Block] = []
    current = Block()
    depth = 0
    for line in lines[i:]:
        if _SKIPPED.match(line):
            continue
        if not line.strip() and depth == 0:
            if current.doc or current.code:
                blocks.append(current)
            current = Block()
            continue
        if line.lstrip().startswith("//") and not current.code and depth == 0:
            current.doc.append(_comment_text(line))
            continue
        current.code.append(line)
        code_part = line.split("//", 1)[0]
        depth += code_part.count("{") - code_part.count("}")
    if current.doc or current.code:
        blocks.append(current)
    return intro, blocks


def _paragraphs(comment: list[str]) -> list[nodes.paragraph]:
    """Comment lines as paragraphs (blank comment lines separate them), taken as plain text."""
    text = "\n".join(comment)
    return [nodes.paragraph(p, p) for p in re.split(r"\n\s*\n", text) if p.strip()]


class CppHeaders(SphinxDirective):
    """``.. cpp-headers:: <folder of the installed headers, relative to the docs>``."""

    required_arguments = 1
    option_spec = {"prefix": directives.unchanged}

    def run(self) -> list[nodes.Node]:
        root = (Path(self.env.srcdir) / self.arguments[0]).resolve()
        prefix = self.options.get("prefix", root.name)
        headers = sorted(
            root.rglob("*.hpp"),
            key=lambda p: (FOLDER_ORDER.index(str(p.parent.relative_to(root)).strip(".")), p.name),
        )
        sections = []
        for path in headers:
            self.env.note_dependency(str(path))
            sections.append(self._header_section(path, f"{prefix}/{path.relative_to(root)}"))
        return sections

    def _header_section(self, path: Path, include_name: str) -> nodes.section:
        intro, blocks = parse_header(path.read_text(encoding="utf-8"))
        section = nodes.section(ids=[nodes.make_id("cpp-" + include_name)])
        section += nodes.title(include_name, include_name)
        section += _paragraphs(intro)
        section += nodes.literal_block(
            f'#include "{include_name}"', f'#include "{include_name}"', language="cpp"
        )
        for block in blocks:
            declared = block.declared()
            if declared:
                # The name as text (the search indexes text, not code) and in the general index.
                kind, name = declared
                target_id = nodes.make_id(f"cpp-{include_name}-{name}")
                section += addnodes.index(
                    entries=[("single", f"{name} (C++, {include_name})", target_id, "", None)]
                )
                heading = nodes.paragraph(ids=[target_id])
                heading += nodes.strong(name, name)
                heading += nodes.Text(f" ({kind})")
                section += heading
            section += _paragraphs(block.doc)
            if block.code:
                code = "\n".join(block.code)
                section += nodes.literal_block(code, code, language="cpp")
        return section


def setup(app: Sphinx) -> dict[str, object]:
    app.add_directive("cpp-headers", CppHeaders)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
