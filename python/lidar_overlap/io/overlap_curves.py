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

from .. import _checks, _reading
from ..forward.result_checks import frozen

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
_DECIMAL_COMMA = re.compile(r"\d,\d")


@dataclass(frozen=True, eq=False)
class OverlapCurve:
    """A measured overlap curve: ``ranges`` (m), ``overlap`` (G, relative or absolute), ``sigma``
    (1-sigma error per point, or None when the file gives none), ``header`` (the header lines)
    and ``source`` (the file name)."""

    ranges: np.ndarray
    overlap: np.ndarray
    sigma: Optional[np.ndarray]
    header: Tuple[str, ...] = ()
    source: str = "a curve"

    def __post_init__(self) -> None:
        """Checked as the reader checks a file (finite values, ranges > 0 strictly increasing, one
        overlap and sigma > 0 per range), the arrays kept as read-only copies."""
        z = _checks.real_array("ranges", self.ranges, ndim=1)
        if z.size == 0 or not (np.all(np.isfinite(z)) and z[0] > 0 and np.all(np.diff(z) > 0)):
            raise ValueError(
                "ranges is invalid: expected finite ranges > 0 m, strictly increasing, at least one"
            )
        values = {"ranges": z}
        for name in ("overlap", "sigma"):
            given = getattr(self, name)
            if given is None and name == "sigma":
                continue
            a = _checks.real_array(name, given, ndim=1)
            if a.shape != z.shape or not np.all(np.isfinite(a)):
                raise ValueError(
                    f"{name} is invalid: expected {z.size} finite values, one per range"
                )
            if name == "sigma" and not np.all(a > 0):
                raise ValueError("sigma is invalid: expected values > 0")
            values[name] = a
        for name, a in values.items():
            object.__setattr__(self, name, frozen(a))
        if not isinstance(self.header, tuple) or not all(isinstance(h, str) for h in self.header):
            raise ValueError(
                f"header = {_checks.shown(self.header)} is invalid: expected a tuple of strings"
            )
        if not isinstance(self.source, str):
            raise ValueError(f"source = {_checks.shown(self.source)} is invalid: expected a name")

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return (
            np.array_equal(self.ranges, other.ranges)
            and np.array_equal(self.overlap, other.overlap)
            and (
                self.sigma is other.sigma is None
                or (
                    self.sigma is not None
                    and other.sigma is not None
                    and np.array_equal(self.sigma, other.sigma)
                )
            )
            and self.header == other.header
            and self.source == other.source
        )

    __hash__ = None  # type: ignore[assignment]  # holds arrays

    def __reduce__(self):
        return (type(self), (self.ranges, self.overlap, self.sigma, self.header, self.source))

    def within(self, z_low: float, z_high: float) -> "OverlapCurve":
        """The points with z_low <= range <= z_high (m); ValueError when fewer than 2 remain."""
        z_low, z_high = _checks.real("z_low", z_low), _checks.real("z_high", z_high)
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
        _refuse_decimal_comma(name, number, text)
        cells = [c for c in _SPLIT.split(text) if c]
        values = _numbers(name, number, cells)
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
            number_or_none = _reading.number(cell)  # ASCII decimals only
            value = math.nan if number_or_none is None else number_or_none
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


def _numbers(name: str, number: int, cells) -> Optional[List[float]]:
    """The cells as numbers, or None for a header line; a cell that Python would read as a number
    but the format does not (Unicode digits, '_' between digits) is a ValueError naming it."""
    values = [_reading.number(c) for c in cells]
    for column, (cell, value) in enumerate(zip(cells, values), start=1):
        if value is None and _python_reads(cell):
            raise ValueError(
                f"{name}: line {number}, column {column}: {cell!r} is invalid: expected a number "
                "in ASCII digits with '.' as the decimal point (no '_', no other digits)"
            )
    numbers = [v for v in values if v is not None]
    return numbers if len(numbers) == len(values) else None


def _python_reads(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


def _refuse_decimal_comma(name: str, number: int, text: str) -> None:
    """A row whose fields are separated by blanks or ';' and hold a comma between digits
    (``150 0,250``, as spreadsheets with a decimal comma export it) would read as three numbers:
    refused, naming the line."""
    fields = [f for f in re.split(r"[\s;]+", text) if f]
    if len(fields) < 2 or not any(_DECIMAL_COMMA.search(f) for f in fields):
        return
    if all(_reading.number(f.replace(",", ".")) is not None for f in fields):
        raise ValueError(
            f"{name}: line {number}: {text!r} is invalid: it reads as numbers with a decimal "
            "comma; expected '.' as the decimal point (and ',', ';' or blanks between columns)"
        )


def far_range_noise(ranges, overlap, interval: Tuple[float, float]) -> float:
    """The 1-sigma noise of a curve from its scatter over ``interval`` = (z_low, z_high) in m, where
    the curve is nearly flat (beyond full overlap).

    Estimator: 1.4826 x MAD(first differences) / sqrt(2). Differences of neighbours remove a slow
    trend (the last approach to 1) that a plain standard deviation would count as noise, the MAD
    ignores isolated spikes, and /sqrt(2) undoes the differencing for independent points. Points of
    a smoothed curve are correlated, which makes this an underestimate; a curve clipped to a
    constant gives 0 (refused: it has no usable scatter there).
    """
    z = _checks.real_array("ranges", ranges, ndim=1)
    g = _checks.real_array("overlap", overlap, ndim=1)
    if g.shape != z.shape:
        raise ValueError(
            f"overlap has {g.size} values for {z.size} ranges: expected one value per range"
        )
    if not isinstance(interval, (tuple, list, np.ndarray)) or len(interval) != 2:
        raise ValueError(
            f"interval = {_checks.shown(interval)} is invalid: expected (z_low, z_high) in m"
        )
    z_low, z_high = (_checks.real("interval", v) for v in interval)
    for name, values in (("ranges", z), ("overlap", g)):
        bad = ~np.isfinite(values)
        if bad.any():
            i = int(np.argmax(bad))
            raise _checks.refused(
                f"{name}[{i}]",
                float(values[i]),
                "finite values",
                f"{name}[{i}] = {values[i]:g} is invalid (range {z[i]:g} m): expected finite "
                "values; drop that point (its range and overlap) first",
            )
    if not z_low < z_high:
        raise ValueError(f"interval = ({z_low:g}, {z_high:g}) m is invalid: expected low < high")
    inside = (z >= z_low) & (z <= z_high)
    if inside.sum() < MIN_NOISE_POINTS:
        raise ValueError(
            f"interval = ({z_low:g}, {z_high:g}) m holds {int(inside.sum())} points of the curve "
            f"(ranges {z[0]:g} to {z[-1]:g} m): expected at least {MIN_NOISE_POINTS}"
        )
    sigma = difference_scatter(g[inside])
    if not sigma > 0:
        raise ValueError(
            f"interval = ({z_low:g}, {z_high:g}) m: the curve has no scatter there (constant or "
            "quantised values); choose an interval where it is measured, not clipped"
        )
    return sigma


def difference_scatter(values: np.ndarray) -> float:
    """1.4826 x MAD(first differences of ``values``) / sqrt(2): the 1-sigma scatter of a nearly
    flat stretch of a curve, in the units of ``values`` (unchecked: at least 2 finite values)."""
    d = np.diff(values)
    return MAD_TO_SIGMA * float(np.median(np.abs(d - np.median(d)))) / math.sqrt(2.0)
