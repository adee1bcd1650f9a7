"""``lidar-overlap fit SCENARIO.toml MEASUREMENTS.csv --free PATH ...``: the scenario's system is
the start, its ``[run]`` method and options the model, the CSV the data; writes ``<name>_fit.csv``
(the parameters with their uncertainties) and ``<name>_fit.png``, and prints the summary.

The measurements file is UTF-8 CSV: ``#`` lines are comments, then a header ``range_m,overlap`` or
``range_m,overlap,sigma`` (m, G, the 1-sigma error of G), then one row per range. Every error names
the file, the line and the column.
"""

from __future__ import annotations

from pathlib import Path
from typing import List

from .. import _files
from ..analysis.fitting.fit import fit
from ..io.overlap_curves import read_measurements
from ..io.scenario import Scenario


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
