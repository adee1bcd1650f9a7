"""A series of overlap curves of one instrument (one per day, say) with a date and covariates each.

The file layout read by :func:`read_overlap_series` is a CSV with one row per curve::

    date,internal_temperature_K,quality,candidates,14.985,29.970,...
    2013-04-06,292.315,2,59,4.0774e-06,...

The first column is ``date`` (ISO 8601: ``YYYY-MM-DD`` or ``YYYY-MM-DDThh:mm[:ss]``, strictly
increasing); then the covariates, each a column whose header is a name; then one column per range
gate, whose header is the range in m (ASCII decimals, > 0, strictly increasing: unsorted or
duplicate ranges are refused). Covariates may be ``nan`` (a missing value: the fits that use a
covariate refuse it there); the overlap values must be finite. Every error names the file, the line
and the column.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Dict, List

import numpy as np

from .. import _checks, _reading, _values
from .._pickling import same_value
from ..analysis.datasets import range_coordinate, xarray
from .overlap_curves import MAX_CSV_BYTES, MAX_ROWS

#: The first column's header.
DATE_COLUMN = "date"
_DATE = re.compile(r"\d{4}-\d{2}-\d{2}(?:T\d{2}:\d{2}(?::\d{2})?)?\Z")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
#: Dates are kept to the second.
DATE_UNIT = "datetime64[s]"


@dataclass(frozen=True, eq=False)
class OverlapSeries:
    """Overlap curves of one instrument: ``ranges`` (m, n_ranges), ``curves`` (G, relative or
    absolute, n_curves x n_ranges), ``dates`` (numpy datetime64, one per curve, strictly
    increasing), ``covariates`` (read-only mapping name -> float array of one value per curve, NaN
    where missing) and ``source`` (the file name)."""

    ranges: np.ndarray
    curves: np.ndarray
    dates: np.ndarray
    covariates: Mapping = dataclasses.field(default_factory=dict)
    source: str = "a series"

    def __post_init__(self) -> None:
        """Checked as the reader checks a file; arrays kept as read-only copies."""
        z = _checks.ranges("ranges", self.ranges)
        if z[0] <= 0:
            raise ValueError(f"ranges[0] = {z[0]!r} is invalid: expected ranges > 0 m")
        curves = _values.array(2)("curves", self.curves)
        if curves.shape[1] != z.size or curves.shape[0] == 0:
            raise ValueError(
                f"curves has shape {curves.shape}: expected (n_curves >= 1, {z.size}), one column "
                "per range"
            )
        dates = _dates("dates", self.dates, curves.shape[0])
        if not isinstance(self.covariates, Mapping):
            raise ValueError(
                f"covariates = {_checks.shown(self.covariates)} is invalid: expected a mapping of "
                "names to one value per curve"
            )
        covariates = {}
        for key, value in self.covariates.items():
            if not isinstance(key, str) or not _NAME.match(key):
                raise ValueError(
                    f"covariates key {_checks.shown(key)} is invalid: expected a name (letters, "
                    "digits, '_')"
                )
            a = _values.array(1, nan=True)(f"covariates[{key!r}]", value)
            if a.size != curves.shape[0]:
                raise ValueError(
                    f"covariates[{key!r}] has {a.size} values for {curves.shape[0]} curves: "
                    "expected one per curve"
                )
            covariates[key] = a
        for name, value in (("ranges", _values.frozen(z)), ("curves", curves), ("dates", dates)):
            object.__setattr__(self, name, value)
        object.__setattr__(self, "covariates", _values.FrozenMap(covariates))
        object.__setattr__(self, "source", _values.text("source", self.source))

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return (
            all(same_value(getattr(self, n), getattr(other, n)) for n in ("ranges", "curves"))
            and np.array_equal(self.dates, other.dates)
            and list(self.covariates) == list(other.covariates)
            and all(same_value(self.covariates[k], other.covariates[k]) for k in self.covariates)
            and self.source == other.source
        )

    __hash__ = None  # type: ignore[assignment]  # holds arrays

    def __reduce__(self):
        covariates = {k: np.array(v) for k, v in self.covariates.items()}
        return (type(self), (self.ranges, self.curves, self.dates, covariates, self.source))

    def __len__(self) -> int:
        return int(self.curves.shape[0])

    def select(self, mask) -> "OverlapSeries":
        """The curves where ``mask`` (booleans, one per curve) is True, e.g.
        ``series.select(series.covariates["quality"] >= 1)``; ValueError when none remain."""
        keep = np.asarray(mask)
        if keep.dtype != bool or keep.shape != (len(self),):
            raise ValueError(
                f"mask = {_checks.shown(mask)} is invalid: expected {len(self)} booleans, one per "
                "curve"
            )
        if not keep.any():
            raise ValueError("mask selects no curve: expected at least one True")
        return OverlapSeries(
            self.ranges,
            self.curves[keep],
            self.dates[keep],
            {k: v[keep] for k, v in self.covariates.items()},
            self.source,
        )

    def within(self, z_low: float, z_high: float) -> "OverlapSeries":
        """The range gates with z_low <= range <= z_high (m); ValueError when none remain."""
        z_low, z_high = _checks.real("z_low", z_low), _checks.real("z_high", z_high)
        keep = (self.ranges >= z_low) & (self.ranges <= z_high)
        if not keep.any():
            raise ValueError(
                f"within: [{z_low:g}, {z_high:g}] m holds no range of {self.source} (ranges "
                f"{self.ranges[0]:g} to {self.ranges[-1]:g} m)"
            )
        return dataclasses.replace(self, ranges=self.ranges[keep], curves=self.curves[:, keep])

    def to_dataset(self) -> Any:
        """An ``xarray.Dataset``: ``overlap`` (date, range), the covariates as coordinates along
        ``date`` (needs xarray)."""
        xr = xarray("OverlapSeries.to_dataset")
        coords: Dict[str, Any] = {"date": self.dates, "range": range_coordinate(self.ranges)}
        coords.update({k: ("date", np.asarray(v)) for k, v in self.covariates.items()})
        return xr.Dataset(
            {"overlap": (("date", "range"), np.asarray(self.curves))},
            coords=coords,
            attrs={"source": self.source},
        )


def _dates(name: str, value: Any, n: int) -> np.ndarray:
    """``value`` as read-only datetime64[s], one per curve, strictly increasing."""
    a = np.asarray(value) if not isinstance(value, (str, bytes)) else None
    if a is None or a.dtype.kind != "M" or a.ndim != 1:
        raise ValueError(
            f"{name} = {_checks.shown(value)} is invalid: expected a 1-D numpy datetime64 array"
        )
    if a.size != n:
        raise ValueError(f"{name} has {a.size} dates for {n} curves: expected one per curve")
    a = a.astype(DATE_UNIT)
    if np.isnat(a).any() or not np.all(a[1:] > a[:-1]):
        raise ValueError(f"{name} is invalid: expected dates (no NaT), strictly increasing")
    a.setflags(write=False)
    return a


def read_overlap_series(path) -> OverlapSeries:
    """The series in ``path`` (the layout of the module docstring); ValueError naming the file, the
    line and the column for a ragged row, a number not in ASCII decimals (decimal commas, other
    digits), a non-finite overlap, unsorted or duplicate ranges or dates, or no data."""
    name = str(path)
    lines = _reading.read_text(
        path,
        MAX_CSV_BYTES,
        "the overlap series",
        "a CSV file 'date,<covariates>,<range in m>,...' with one row per curve",
    ).splitlines()
    rows = [(i, t) for i, t in ((i, line.strip()) for i, line in enumerate(lines, 1)) if t]
    rows = [(i, t) for i, t in rows if not t.startswith("#")]
    if not rows:
        raise ValueError(f"{name}: no header: expected 'date,<covariates>,<range in m>,...'")
    header_line, header_text = rows[0]
    header = [c.strip() for c in header_text.split(",")]
    if header[0] != DATE_COLUMN:
        raise ValueError(
            f"{name}: line {header_line}, column 1: {header[0]!r} is invalid: expected "
            f"'{DATE_COLUMN}'"
        )
    covariates, ranges = _header(name, header_line, header[1:])
    width = len(header)
    dates: List[np.datetime64] = []
    values: List[List[float]] = []
    for line, text in rows[1:]:
        cells = [c.strip() for c in text.split(",")]
        if len(cells) != width:
            raise ValueError(
                f"{name}: line {line}: {len(cells)} values, expected {width} (a date, "
                f"{len(covariates)} covariates and {len(ranges)} ranges); a decimal comma reads "
                "as more values: expected '.' as the decimal point"
            )
        if not cells[0].isascii() or not _DATE.match(cells[0]):
            raise ValueError(
                f"{name}: line {line}, column 1 (date): {cells[0]!r} is invalid: expected "
                "YYYY-MM-DD or YYYY-MM-DDThh:mm[:ss]"
            )
        try:
            date = np.datetime64(cells[0], "s")
        except ValueError:
            raise ValueError(
                f"{name}: line {line}, column 1 (date): {cells[0]!r} is not a calendar date"
            ) from None
        if dates and not date > dates[-1]:
            raise ValueError(
                f"{name}: line {line}, column 1 (date): {cells[0]} does not follow {dates[-1]}: "
                "dates must be strictly increasing"
            )
        row = []
        for column, cell in enumerate(cells[1:], start=2):
            value = _reading.number(cell)  # ASCII decimals only
            curve_value = column > 1 + len(covariates)
            if value is None or (curve_value and not math.isfinite(value)):
                key = header[column - 1]
                what = "a finite number" if curve_value else "a number or nan"
                raise ValueError(
                    f"{name}: line {line}, column {column} ({key}): {cell!r} is invalid: "
                    f"expected {what} in ASCII digits with '.' as the decimal point"
                )
            row.append(value)
        dates.append(date)
        values.append(row)
        if len(values) > MAX_ROWS:
            raise ValueError(f"{name}: more than {MAX_ROWS} rows")
    if not values:
        raise ValueError(f"{name}: no data: expected one row per curve after the header")
    data = np.array(values)
    k = len(covariates)
    return OverlapSeries(
        np.array(ranges),
        data[:, k:],
        np.array(dates, dtype=DATE_UNIT),
        {key: data[:, i] for i, key in enumerate(covariates)},
        name,
    )


def _header(name: str, line: int, cells: List[str]):
    """(covariate names, ranges in m) from the header cells after ``date``."""
    covariates: List[str] = []
    ranges: List[float] = []
    for column, cell in enumerate(cells, start=2):
        value = _reading.number(cell)
        where = f"{name}: line {line}, column {column}"
        if value is None:
            if ranges:
                raise ValueError(
                    f"{where}: {cell!r} is invalid: expected a range in m in ASCII decimals "
                    "(covariates come before the ranges)"
                )
            if not _NAME.match(cell) or cell in covariates or cell == DATE_COLUMN:
                raise ValueError(
                    f"{where}: {cell!r} is invalid: expected a new covariate name (ASCII "
                    "letters, digits, '_') or a range in m"
                )
            covariates.append(cell)
            continue
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{where}: range {cell!r} is invalid: expected a finite range > 0 m")
        if ranges and not value > ranges[-1]:
            raise ValueError(
                f"{where}: range {cell} m does not follow {ranges[-1]:g} m: ranges must be "
                "strictly increasing (no duplicates)"
            )
        ranges.append(value)
    if not ranges:
        raise ValueError(
            f"{name}: line {line}: no range columns: expected ranges in m after the covariates"
        )
    return covariates, ranges
