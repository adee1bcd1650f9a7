"""Measured overlap curves from text files, and the noise of a curve from its far-range scatter.

Formats read by :func:`read_overlap_curve`:

- two-column text as lidar networks publish retrieved overlap profiles: one or more header lines
  (any text that is not two numbers, e.g. ``height(m)   overlap`` or a row count), then one row
  ``range, overlap`` per line, separated by a comma, whitespace or both;
- CSV with the header ``range_m,overlap`` or ``range_m,overlap,sigma`` (the command line's
  measurements file), ``#`` lines being comments: :func:`read_measurements`, on the one CSV reader
  :func:`read_csv_table` (which also reads the telecover's ``range_m,<sector>,...`` files).

Ranges are in m and strictly increasing; overlap is relative or absolute G (any finite number:
retrieved curves go slightly negative at the first bins). Every error names the file and the line.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import List, Optional, Sequence, Tuple

import numpy as np

from .. import _reading

#: The most rows read.
MAX_ROWS = 100_000
#: Points the noise estimate needs in its interval (fewer give a scatter too uncertain to use).
MIN_NOISE_POINTS = 10
#: MAD of a normal distribution times this is its standard deviation.
MAD_TO_SIGMA = 1.482602218505602
_SPLIT = re.compile(r"[,\s;]+")
#: The measurements CSV's columns (sigma optional).
CSV_COLUMNS = ("range_m", "overlap", "sigma")
#: The largest CSV file read (comments included); a larger one is refused whole, never cut.
MAX_CSV_BYTES = 64_000_000


@dataclass(frozen=True, eq=False)
class OverlapCurve:
    """A measured overlap curve: ``ranges`` (m), ``overlap`` (G, relative or absolute), ``sigma``
    (1-sigma error per point, or None when the file gives none), ``header`` (the header lines)
    and ``source`` (the file name)."""

    ranges: np.ndarray
    overlap: np.ndarray
    sigma: Optional[np.ndarray]
    header: Tuple[str, ...]
    source: str

    def within(self, z_low: float, z_high: float) -> "OverlapCurve":
        """The points with z_low <= range <= z_high (m); ValueError when fewer than 2 remain."""
        keep = (self.ranges >= z_low) & (self.ranges <= z_high)
        if keep.sum() < 2:
            raise ValueError(
                f"within: [{z_low:g}, {z_high:g}] m holds {int(keep.sum())} points of "
                f"{self.source} (ranges {self.ranges[0]:g} to {self.ranges[-1]:g} m): "
                "expected at least 2"
            )
        return OverlapCurve(
            self.ranges[keep],
            self.overlap[keep],
            None if self.sigma is None else self.sigma[keep],
            self.header,
            self.source,
        )


def read_overlap_curve(path) -> OverlapCurve:
    """The curve in ``path`` (either format of the module docstring); ValueError naming the file
    and line for unreadable text, a row of the wrong length, a non-finite value, a range <= 0 or
    ranges that do not increase."""
    name = str(path)
    lines = _reading.read_text(
        path, 200 * MAX_ROWS, "the overlap curve", "two columns of range (m) and overlap"
    ).splitlines()
    head = next((t for t in (line.strip() for line in lines) if t and not t.startswith("#")), "")
    if tuple(c.strip() for c in head.split(",")) in (CSV_COLUMNS[:2], CSV_COLUMNS):
        z, g, sigma = read_measurements(path)
        return OverlapCurve(
            z.copy(), g.copy(), None if sigma is None else sigma.copy(), (head,), name
        )
    header: List[str] = []
    rows: List[List[float]] = []
    width = None
    for number, line in enumerate(lines, start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        cells = [c for c in _SPLIT.split(text) if c]
        values = _numbers(cells)
        if values is None or len(values) < 2:
            if rows:
                raise ValueError(
                    f"{name}: line {number}: {text!r} is invalid: expected numbers "
                    "'range, overlap' (header lines only come before the data)"
                )
            header.append(text)
            continue
        width = width or len(values)
        if len(values) != width or width > 3:
            raise ValueError(
                f"{name}: line {number}: {len(values)} values, expected "
                f"{width if width <= 3 else 2} (range, overlap and an optional sigma)"
            )
        bad = [i for i, v in enumerate(values) if not math.isfinite(v)]
        if bad:
            raise ValueError(
                f"{name}: line {number}, column {bad[0] + 1}: {cells[bad[0]]!r} is invalid: "
                "expected a finite number"
            )
        if values[0] <= 0 or (rows and not values[0] > rows[-1][0]):
            raise ValueError(
                f"{name}: line {number}, column 1 (range): {values[0]:g} is invalid: expected "
                "ranges > 0 m, strictly increasing"
            )
        if width == 3 and not values[2] > 0:
            raise ValueError(
                f"{name}: line {number}, column 3 (sigma): {values[2]:g} is invalid: expected > 0"
            )
        rows.append(values)
        if len(rows) > MAX_ROWS:
            raise ValueError(f"{name}: more than {MAX_ROWS} rows")
    if not rows:
        raise ValueError(f"{name}: no data: expected rows 'range, overlap' after any header lines")
    data = np.array(rows, dtype=float)
    sigma = data[:, 2].copy() if width == 3 else None
    return OverlapCurve(data[:, 0].copy(), data[:, 1].copy(), sigma, tuple(header), name)


def read_measurements(path) -> Tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(ranges, overlap, sigma or None) from a measurements CSV; ValueError naming file, line and
    column."""
    data, sigma = read_csv_table(path, CSV_COLUMNS[:2], signed=("overlap",))
    return data[:, 0], data[:, 1], sigma


def read_csv_table(
    path, columns: Sequence[str], signed: Sequence[str] = ()
) -> Tuple[np.ndarray, np.ndarray | None]:
    """(rows x ``columns``, the optional last column ``sigma`` or None) from a CSV whose header is
    ``columns`` (the first ``range_m``, strictly increasing), optionally followed by ``sigma``.
    Values are finite, and > 0 but in the ``signed`` columns. ValueError naming file, line and
    column."""
    name, header_text = str(path), ",".join(columns)
    lines = _reading.read_text(
        path, MAX_CSV_BYTES, "the measurements", f"a CSV file with the columns '{header_text}'"
    ).splitlines()
    rows: List[List[float]] = []
    header = None
    for number, line in enumerate(lines, start=1):
        text = line.strip()
        if not text or text.startswith("#"):
            continue
        cells = [c.strip() for c in text.split(",")]
        if header is None:
            header = tuple(cells)
            if header not in (tuple(columns), (*columns, "sigma")):
                raise ValueError(
                    f"{name}: line {number}: header {text!r} is invalid: expected '{header_text}' "
                    f"or '{header_text},sigma'"
                )
            continue
        if len(cells) != len(header):
            raise ValueError(
                f"{name}: line {number}: {len(cells)} values, expected {len(header)} "
                f"({','.join(header)})"
            )
        row = []
        for column, (key, cell) in enumerate(zip(header, cells), start=1):
            try:
                value = float(cell)
            except ValueError:
                value = float("nan")
            if not math.isfinite(value) or (key not in signed and value <= 0):
                what = "a finite number" if key in signed else "a finite number > 0"
                raise ValueError(
                    f"{name}: line {number}, column {column} ({key}): {cell!r} is invalid: "
                    f"expected {what}"
                )
            row.append(value)
        if rows and not row[0] > rows[-1][0]:
            raise ValueError(
                f"{name}: line {number}, column 1 (range_m): {row[0]:g} does not follow "
                f"{rows[-1][0]:g}: ranges must be strictly increasing"
            )
        rows.append(row)
        if len(rows) > MAX_ROWS:
            raise ValueError(f"{name}: more than {MAX_ROWS} rows")
    if header is None or not rows:
        raise ValueError(
            f"{name}: no {'header' if header is None else 'data'}: expected a header "
            f"'{header_text},sigma' (sigma optional) and one row per range"
        )
    data = np.array(rows)
    return data[:, : len(columns)], (data[:, -1] if len(header) > len(columns) else None)


def _numbers(cells):
    try:
        return [float(c) for c in cells]
    except ValueError:
        return None


def far_range_noise(ranges, overlap, interval: Tuple[float, float]) -> float:
    """The 1-sigma noise of a curve from its scatter over ``interval`` = (z_low, z_high) in m, where
    the curve is nearly flat (beyond full overlap).

    Estimator: 1.4826 x MAD(first differences) / sqrt(2). Differences of neighbours remove a slow
    trend (the last approach to 1) that a plain standard deviation would count as noise, the MAD
    ignores isolated spikes, and /sqrt(2) undoes the differencing for independent points. Points of
    a smoothed curve are correlated, which makes this an underestimate; a curve clipped to a
    constant gives 0 (refused: it has no usable scatter there).
    """
    z = np.asarray(ranges, dtype=float)
    g = np.asarray(overlap, dtype=float)
    z_low, z_high = (float(v) for v in interval)
    if not z_low < z_high:
        raise ValueError(f"interval = ({z_low:g}, {z_high:g}) m is invalid: expected low < high")
    inside = (z >= z_low) & (z <= z_high)
    if inside.sum() < MIN_NOISE_POINTS:
        raise ValueError(
            f"interval = ({z_low:g}, {z_high:g}) m holds {int(inside.sum())} points of the curve "
            f"(ranges {z[0]:g} to {z[-1]:g} m): expected at least {MIN_NOISE_POINTS}"
        )
    d = np.diff(g[inside])
    sigma = MAD_TO_SIGMA * float(np.median(np.abs(d - np.median(d)))) / math.sqrt(2.0)
    if not sigma > 0:
        raise ValueError(
            f"interval = ({z_low:g}, {z_high:g}) m: the curve has no scatter there (constant or "
            "quantised values); choose an interval where it is measured, not clipped"
        )
    return sigma
