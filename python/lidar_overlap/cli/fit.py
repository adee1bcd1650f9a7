"""``lidar-overlap fit SCENARIO.toml MEASUREMENTS.csv --free PATH ...``: the scenario's system is
the start, its ``[run]`` method and options the model, the CSV the data; writes ``<name>_fit.csv``
(the parameters with their uncertainties) and ``<name>_fit.png``, and prints the summary.

The measurements file is UTF-8 CSV: ``#`` lines are comments, then a header ``range_m,overlap`` or
``range_m,overlap,sigma`` (m, G, the 1-sigma error of G), then one row per range. Every error names
the file, the line and the column.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import List, Sequence, Tuple

import numpy as np

from .. import _files, _reading
from ..analysis.fitting.fit import fit
from ..io.scenario import Scenario

COLUMNS = ("range_m", "overlap", "sigma")
#: The most rows read (as many as a scenario's ranges).
MAX_ROWS = 100_000
#: The largest file read (comments included); a larger one is refused whole, never cut.
MAX_BYTES = 64_000_000


def read_measurements(path) -> Tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """(ranges, overlap, sigma or None) from a measurements CSV; ValueError naming file, line and
    column."""
    data, sigma = read_table(path, COLUMNS[:2], signed=("overlap",))
    return data[:, 0], data[:, 1], sigma


def read_table(
    path, columns: Sequence[str], signed: Sequence[str] = ()
) -> Tuple[np.ndarray, np.ndarray | None]:
    """(rows x ``columns``, the optional last column ``sigma`` or None) from a CSV whose header is
    ``columns`` (the first ``range_m``, strictly increasing), optionally followed by ``sigma``.
    Values are finite, and > 0 but in the ``signed`` columns. ValueError naming file, line and
    column."""
    name, header_text = str(path), ",".join(columns)
    lines = _reading.read_text(
        path, MAX_BYTES, "the measurements", f"a CSV file with the columns '{header_text}'"
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


def fit_scenario(
    scenario: Scenario,
    measurements: Path,
    free: List[str],
    out: Path,
    method=None,
    normalize=None,
    extinction_bias: bool = False,
):
    """Fit, then write ``<name>_fit.csv`` and ``<name>_fit.png`` into ``out``; returns (result,
    files, note). ``normalize``: None or (z_low, z_high) in m; ``extinction_bias``: as
    :func:`lidar_overlap.fit`."""
    z, g, sigma = read_measurements(measurements)
    model, threads = scenario.method_object(method), scenario.threads
    result = fit(
        scenario.system, z, g, sigma, free=free, method=model, threads=threads,
        normalize=normalize, extinction_bias=extinction_bias,
    )  # fmt: skip
    header = [f"# scenario: {scenario.name}", f"# measurements: {measurements}"]
    if normalize is not None:
        header.append(f"# normalize: model and data each by their mean over {normalize} m")
    files, note = write_fit(
        result,
        out / f"{scenario.name}_fit",
        header,
        f"{scenario.name}: fit to {Path(measurements).name}",
    )
    return result, files, note


def write_fit(result, stem: Path, header: List[str], title: str):
    """``<stem>.csv`` (``header`` lines, the model and chi-square, then the parameters) and
    ``<stem>.png`` (the result's plot); returns (files, note about a plot not written, or None)."""
    stem.parent.mkdir(parents=True, exist_ok=True)
    lines = header + [
        f"# model: {result.result.method}, loss {result.loss}",
        f"# chi_square: {result.chi_square!r}",
        f"# degrees_of_freedom: {result.degrees_of_freedom}",
        f"# reduced_chi_square: {result.reduced_chi_square!r}",
        f"# covariance_scaled_by_reduced_chi_square: {result.covariance_scaled}",
        "parameter,value,uncertainty,unit,start",
    ]
    lines += [f"{p},{v!r},{u!r},{unit},{s!r}" for p, v, u, unit, s in result.table()]
    with _files.replacing(f"{stem}.csv", "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    files, note = [f"{stem}.csv"], None
    try:
        fig = result.plot()
    except ImportError:
        note = (
            f"{stem}.png not written: plotting needs matplotlib: pip install 'lidar-overlap[plot]'"
        )
    else:
        fig.suptitle(title, fontsize=9)
        with _files.replacing_path(Path(f"{stem}.png")) as temporary:
            fig.savefig(temporary, dpi=120)
        files.append(f"{stem}.png")
    return files, note
