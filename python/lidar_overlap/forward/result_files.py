"""An :class:`OverlapResult` written to and read from CSV and NetCDF files, exactly or not at all.

What a file says about the result (its method, tolerance, error kind and system) is written from
the result itself: a caller's extra attributes may add keys but not replace those, and a reader
takes header keys only before the data, each once. A header that names a system which cannot be
rebuilt is an error, never a result with ``system=None``.
"""

from __future__ import annotations

import math
import os
import re
import stat
from datetime import datetime, timezone
from typing import Any, Dict, Optional

import numpy as np

from .. import _checks, _files, _reading
from .._core import __version__
from ..model.system_attributes import SYSTEM_PREFIXES, system_from_attributes

CSV_COLUMNS = ("range_m", "overlap", "error_estimate")
#: Keys a file's header holds for the result itself; a caller's ``attrs`` may not use them.
RESERVED = (
    "format",
    "method",
    "tolerance",
    "error_kind",
    "lidar_overlap_version",
    "system",
    "turbulence_paths",
    "turbulence_realizations",
)
#: NetCDF attributes the writer sets for provenance (CF conventions); a caller's ``attrs`` may not
#: replace them (``title`` and ``references`` it may).
NETCDF_RESERVED = ("Conventions", "source", "history")
#: The line that closes a CSV result, with its number of rows: a file cut short (even inside the
#: last number, which would still read as a number) lacks it and is refused.
ROWS_TRAILER = "# rows: "
#: The largest CSV result read whole (about 10^7 ranges); a larger file is refused, not cut.
MAX_CSV_BYTES = 1_000_000_000
_KEY = re.compile(r"[A-Za-z_][A-Za-z0-9_.\-]*\Z")
IO_HINT = (
    "reading and writing NetCDF needs xarray and h5netcdf (with h5py): "
    "pip install 'lidar-overlap[io]'"
)


def header(result, attrs: Optional[Dict[str, Any]], reserved=RESERVED) -> Dict[str, Any]:
    """The result's own attributes, then the caller's ``attrs``, each checked to read back as
    given: a key the result writes itself (or a system key) is a ValueError naming it."""
    extra = {} if attrs is None else attrs
    if not isinstance(extra, dict):
        raise ValueError(
            f"attrs = {_checks.shown(attrs)} is invalid: expected a dict of extra header keys"
        )
    for key, value in extra.items():
        if not isinstance(key, str) or not _KEY.match(key):
            raise ValueError(
                f"attrs key {_checks.shown(key)} is invalid: expected a name of letters, digits, "
                "'_', '.' or '-' (starting with a letter or '_')"
            )
        if key in reserved or key.startswith(SYSTEM_PREFIXES):
            raise ValueError(
                f"attrs[{key!r}] is invalid: the result writes {key!r} itself (method, tolerance, "
                "error kind and system come from the result); choose another name"
            )
        if not _reads_back(value):
            raise ValueError(
                f"attrs[{key!r}] = {_checks.shown(value)} is invalid: expected a finite number or "
                "a one-line text that does not read as a number"
            )
    return {**result.attributes(), **extra}


def _reads_back(value: Any) -> bool:
    if isinstance(value, (bool, np.bool_)):
        return False
    if isinstance(value, (int, np.integer)):
        return True
    if isinstance(value, (float, np.floating)):
        return math.isfinite(value)
    if isinstance(value, str):
        return value == " ".join(value.split()) and isinstance(parse_value(value), str)
    return False


def csv_value(value: Any) -> str:
    """A header value as CSV text: floats exactly (repr), anything else on one line."""
    if isinstance(value, (float, np.floating)):
        return repr(float(value))
    return " ".join(str(value).split())


def parse_value(text: str) -> Any:
    """A header value: an int or a float when it is an ASCII number, else the text."""
    for read in (_reading.integer, _reading.number):
        value = read(text)
        if value is not None:
            return value
    return text


def write_csv(result, path, attrs) -> None:
    lines = [f"# {key}: {csv_value(value)}" for key, value in csv_header(result, attrs).items()]
    lines.append(",".join(CSV_COLUMNS))
    for row in zip(result.ranges.tolist(), result.overlap.tolist(), result.error_estimate.tolist()):
        lines.append(",".join(repr(float(v)) for v in row))
    lines.append(f"{ROWS_TRAILER}{result.ranges.size}")
    with _files.replacing(path, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def csv_header(result, attrs) -> Dict[str, Any]:
    head = {"format": "lidar-overlap result", **header(result, attrs)}
    if result.system is not None:
        head["system"] = repr(result.system)
    return head


def read_csv(cls, path, turbulent_cls=None):
    """``cls`` from a CSV file; ``turbulent_cls`` instead when the header says the curve is a mean
    through turbulence (``turbulence_paths``), whose two-way mean may exceed 1."""
    text = _reading.read_text(
        path, MAX_CSV_BYTES, "the result", "a file written by OverlapResult.to_csv"
    )
    attrs, rows = _csv_rows(path, text.splitlines())
    data = np.array(rows, dtype=float).reshape(-1, len(CSV_COLUMNS))
    cls, extra = _kind(cls, turbulent_cls, attrs)
    return from_attributes(cls, path, attrs, data[:, 0], data[:, 1], data[:, 2], **extra)


def _kind(cls, turbulent_cls, attrs):
    """(class, its extra fields) of a file's result: ``turbulent_cls`` with its ``paths`` when the
    header names them (a mean through turbulence), else ``cls``."""
    if turbulent_cls is not None and "turbulence_paths" in attrs:
        return turbulent_cls, {"paths": attrs["turbulence_paths"]}
    return cls, {}


def _csv_rows(path, lines):
    """The ``# key: value`` header (before the columns, each key once) and the rows of numbers."""
    attrs: Dict[str, Any] = {}
    rows, columns, count = [], False, None
    for number, line in enumerate(lines, 1):
        line = line.strip()
        if not line:
            continue
        if count is not None:
            raise ValueError(
                f"{path}: line {number} = {_short(line)} is invalid: nothing may follow the "
                "closing row count"
            )
        if columns and line.startswith(ROWS_TRAILER):
            count = _reading.integer(line[len(ROWS_TRAILER) :])
            if count != len(rows):
                raise ValueError(
                    f"{path}: line {number} = {_short(line)}: the file closes with a count of "
                    f"rows that is not the {len(rows)} rows it holds: expected a complete file"
                )
            continue
        if line.startswith("#"):
            if columns:
                raise ValueError(
                    f"{path}: line {number} = {_short(line)} is invalid: header and comment lines "
                    "come before the columns, not among the data"
                )
            key, sep, value = line[1:].partition(":")
            key = key.strip()
            if sep:
                if key in attrs:
                    raise ValueError(
                        f"{path}: line {number}: header key {key!r} appears twice: expected "
                        "each key once"
                    )
                attrs[key] = parse_value(value.strip())
        elif not columns:
            if "method" not in attrs or line.replace(" ", "") != ",".join(CSV_COLUMNS):
                raise ValueError(
                    f"{path}: not a file written by OverlapResult.to_csv: expected '# method:' "
                    f"and the other header lines, then the columns {','.join(CSV_COLUMNS)}"
                )
            columns = True
        else:
            values = [_reading.number(v) for v in line.split(",")]
            if len(values) != len(CSV_COLUMNS) or None in values:
                raise ValueError(
                    f"{path}: line {number} = {_short(line)} is invalid: expected "
                    f"{len(CSV_COLUMNS)} numbers ({','.join(CSV_COLUMNS)})"
                )
            rows.append(values)
    if not columns:
        raise ValueError(
            f"{path}: no columns {','.join(CSV_COLUMNS)}: not a file written by "
            "OverlapResult.to_csv"
        )
    if count is None:
        raise ValueError(
            f"{path}: the file ends without its closing line '{ROWS_TRAILER}N': it was cut "
            "short (a number of its last row may be cut too), or written before result files "
            "closed with a row count; write it again with OverlapResult.to_csv"
        )
    return attrs, rows


def from_attributes(cls, path, attrs: Dict[str, Any], ranges, overlap, error_estimate, **extra):
    """``cls`` from what a file holds (and ``extra`` fields); a ValueError of the class's checks
    names the file."""
    try:
        method = attrs["method"]
        if not isinstance(method, str):
            raise ValueError(f"method = {method!r} is invalid: expected the name of the model")
        kind = str(
            attrs.get("error_kind", "nominal" if method == "fo" else "bound")
        )  # files written before the kind existed
        tolerance = attrs.get("tolerance", math.nan)
        if isinstance(tolerance, str):
            raise ValueError(f"tolerance = {tolerance!r} is invalid: expected a number")
        return cls(
            ranges=np.array(ranges, dtype=float),
            overlap=np.array(overlap, dtype=float),
            method=method,
            error_estimate=np.array(error_estimate, dtype=float),
            system=system_from_attributes(attrs),
            tolerance=float(tolerance),
            error_kind=kind,
            **extra,
        )
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None


def to_xarray(result, attrs):
    xr = xarray()
    now = datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    tolerance = "" if math.isnan(result.tolerance) else f", tolerance={result.tolerance!r}"
    glob = {
        "Conventions": "CF-1.10",
        "title": "Lidar overlap function G(z)",
        "source": f"lidar_overlap {__version__}",
        "history": f"{now}: computed by lidar_overlap {__version__}, "
        f"overlap(method={result.method!r}{tolerance})",
        "references": "Extended overlap function computation method for atmospheric lidars",
        **header(result, attrs, RESERVED + NETCDF_RESERVED),
    }
    if result.system is not None:
        glob["system"] = repr(result.system)
    coord = {"units": "m", "long_name": "range from the transmitting plane", "axis": "X"}
    return xr.Dataset(
        {
            "overlap": (
                "range",
                np.array(result.overlap, dtype=float),
                {
                    "units": "1",
                    "long_name": "lidar overlap function",
                    "comment": "power reaching the detector over the power entering the full "
                    "aperture",
                },
            ),
            "error_estimate": (
                "range",
                np.array(result.error_estimate, dtype=float),
                {
                    "units": "1",
                    "long_name": "estimated absolute error of the overlap function",
                    "comment": "NaN where the method gives no estimate",
                },
            ),
        },
        coords={"range": ("range", np.array(result.ranges, dtype=float), coord)},
        attrs=glob,
    )


def write_netcdf(result, path, attrs, engine) -> None:
    ds = to_xarray(result, attrs)
    encoding = {name: {"_FillValue": None} for name in ("range", "overlap", "error_estimate")}
    engine = engine or netcdf_engine()
    with _files.replacing_path(path) as temporary:
        ds.to_netcdf(temporary, engine=engine, encoding=encoding)


def read_netcdf(cls, path, engine, turbulent_cls=None):
    xr = xarray()
    _regular(path)
    try:
        with xr.open_dataset(path, engine=engine) as ds:
            ds = ds.load()
    except (OSError, ValueError, TypeError, KeyError, IndexError, RuntimeError) as exc:
        reason = " ".join(str(exc).split())[:200] or type(exc).__name__
        raise ValueError(
            f"{path}: not a readable NetCDF file written by OverlapResult.to_netcdf ({reason})"
        ) from None
    attrs = {k: (v.item() if isinstance(v, np.generic) else v) for k, v in ds.attrs.items()}
    if "method" not in attrs or any(
        name not in ds.variables for name in ("range", "overlap", "error_estimate")
    ):
        raise ValueError(
            f"{path}: not a file written by OverlapResult.to_netcdf (no 'method' attribute, or "
            "no 'range', 'overlap' or 'error_estimate')"
        )
    values = [ds[name].values for name in ("range", "overlap", "error_estimate")]
    cls, extra = _kind(cls, turbulent_cls, attrs)
    return from_attributes(cls, path, attrs, *values, **extra)


def _regular(path) -> None:
    """A FIFO or device would block the NetCDF reader: refuse it, and a missing file, by name."""
    try:
        mode = os.stat(path).st_mode
    except OSError as exc:
        raise ValueError(f"{path}: cannot read the result: {exc.strerror or exc}") from None
    if not stat.S_ISREG(mode):
        raise ValueError(
            f"{path}: cannot read the result: not a regular file: expected a NetCDF file written "
            "by OverlapResult.to_netcdf"
        )


def _short(value, limit: int = 80) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def xarray():
    try:
        import xarray
    except ImportError as exc:
        raise ImportError(IO_HINT) from exc
    return xarray


def netcdf_engine() -> str:
    """h5netcdf with its h5py backend if installed, else scipy's NetCDF-3 writer."""
    import importlib.util

    if importlib.util.find_spec("h5netcdf") and importlib.util.find_spec("h5py"):
        return "h5netcdf"
    if importlib.util.find_spec("scipy"):
        return "scipy"
    raise ImportError(IO_HINT)
