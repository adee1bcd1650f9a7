"""``lidar-overlap telecover SCENARIO.toml [--sectors quadrants|N] [--measurements CSV --free PATH
...]``.

Without measurements: the telecover of the scenario's system at its ranges, with its ``[run]``
model, written to ``<name>_telecover.csv`` (``# key: value`` header, then ``range_m``, one
``G_<sector>`` column per sector and one ``deviation_<sector>`` column per sector) and
``<name>_telecover.png`` (the conventional figure).

With measurements: a UTF-8 CSV with the header ``range_m,<sector>,...`` (one deviation column per
sector, in
the order of the sectors: ``north,east,south,west`` for quadrants, ``sector_0,...`` for N sectors)
and an optional last column ``sigma`` (the 1-sigma error of each deviation); :func:`.fit_telecover`
fits the free parameters (ray tracing at the ``[run]`` tolerance) and
``<name>_telecover_fit.csv`` and ``.png`` are written.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import List, Optional

import numpy as np

from .. import _files
from ..analysis.studies.telecover import sector_mask, telecover
from ..analysis.studies.telecover_fit import fit_telecover
from ..forward.result_files import csv_value
from ..forward.validity import rt_ranges_outside
from ..io.overlap_curves import read_csv_table
from ..io.scenario import Scenario
from ..model.aperture_mask import ApertureMask, equal_sectors
from .fit import write_fit


def sectors_argument(text: str) -> ApertureMask:
    """``--sectors``: ``quadrants`` or a number of equal sectors, 2 to 64 (ValueError otherwise)."""
    if text == "quadrants":
        return ApertureMask.quadrants()
    try:
        n = int(text)
    except ValueError:
        n = 0
    if not 2 <= n <= 64:
        raise ValueError(
            f"invalid value {text!r}: expected 'quadrants' or a number of sectors, 2 to 64"
        )
    return equal_sectors(n)


def column(name: str) -> str:
    """A sector's name as a CSV column name."""
    return name.replace(" ", "_")


def compute(scenario: Scenario, mask: ApertureMask, out: Path, method: Optional[str] = None):
    """The telecover of the scenario, written; returns (result, files, notes)."""
    model, threads = scenario.method_object(method), scenario.threads
    result = telecover(scenario.system, scenario.ranges, mask, model, threads=threads)
    lit = np.isfinite(result.deviation).all(axis=0)  # some sector receives light
    if not lit.any():
        raise ValueError(
            f"{scenario.name}: no sector receives light at any range (G = 0 everywhere), so the "
            "telecover deviations are undefined: check the alignment (tilt, offsets) and ranges"
        )
    out.mkdir(parents=True, exist_ok=True)
    stem = out / f"{scenario.name}_telecover"
    header = {
        "format": "lidar-overlap telecover",
        "scenario": scenario.name,
        "description": scenario.description,
        "sectors": " ".join(column(n) for n in result.names),
        "full_overlap_range_m": result.full.full_overlap_range(),
        **result.full.attributes(),
    }
    names = [column(n) for n in result.names]
    lines = [f"# {key}: {csv_value(value)}" for key, value in header.items()]
    lines.append(
        ",".join(["range_m"] + [f"G_{n}" for n in names] + [f"deviation_{n}" for n in names])
    )
    if not lit.all():
        lines.insert(
            -1,
            "# deviation: left empty at ranges where no sector receives light (G = 0: undefined)",
        )
    for z, g, d, light in zip(
        result.ranges.tolist(), result.overlap.T.tolist(), result.deviation.T.tolist(), lit
    ):
        cells = [repr(float(v)) for v in [z, *g]] + [repr(float(v)) if light else "" for v in d]
        lines.append(",".join(cells))
    with _files.replacing(f"{stem}.csv", "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    files, notes = [f"{stem}.csv"], []
    try:
        from matplotlib.figure import Figure
    except ImportError:
        notes.append(
            f"{stem}.png not written: plotting needs matplotlib: pip install 'lidar-overlap[plot]'"
        )
    else:
        fig = Figure(figsize=(6.4, 6.4), constrained_layout=True)
        result.plot(axes=fig.subplots(2, 1, sharex=True))
        fig.suptitle(f"{scenario.name}: telecover ({result.method})", fontsize=9)
        with _files.replacing_path(Path(f"{stem}.png")) as temporary:
            fig.savefig(temporary, dpi=120)
        files.append(f"{stem}.png")
    return result, files, notes


def summary(name: str, result) -> List[str]:
    """The largest |deviation| of each sector beyond the full-overlap range, one line each."""
    z_full = result.full.full_overlap_range()
    if not math.isfinite(z_full):
        return [
            f"{name}: telecover ({result.method}): full overlap nowhere on the grid; no deviations "
            "summarised"
        ]
    beyond = result.ranges >= z_full
    lines = [
        f"{name}: telecover ({result.method}), largest |deviation| beyond full overlap "
        f"({z_full:.4g} m):"
    ]
    for sector, d in zip(result.names, result.deviation[:, beyond]):
        k = int(np.nanargmax(np.abs(d))) if np.isfinite(d).any() else None
        lines.append(
            f"  {sector:<10} "
            + (
                "none (no light)"
                if k is None
                else f"{100 * abs(d[k]):.3g} % at {result.ranges[beyond][k]:.4g} m"
            )
        )
    return lines


def fit(
    scenario: Scenario,
    mask: ApertureMask,
    measurements: Path,
    free: List[str],
    out: Path,
    outside_validity: bool = False,
):
    """Fit the deviations of ``measurements`` by ray tracing at the scenario's ``[run]``
    tolerance (the command line's telecover fit; ``lo.fit_telecover`` takes any model), written;
    returns (FitResult, files, notes). Ranges outside ray tracing's validity are refused (a
    ValueError) unless ``outside_validity``: a fit there reports numbers the model cannot give."""
    names = [column(n) for n in sector_mask(scenario.system, mask).names]
    data, sigma = read_csv_table(measurements, ["range_m"] + names, signed=names)
    outside = rt_ranges_outside(scenario.system, data[:, 0])
    if outside and not outside_validity:
        raise ValueError(
            f"{measurements}: range_m: {outside.rstrip('.')}; pass --outside-validity to fit "
            "there anyway"
        )
    result = fit_telecover(
        scenario.system,
        data[:, 0],
        data[:, 1:].T,
        None if sigma is None else sigma[None, :],
        free=free,
        sectors=mask,
        method=scenario.method_object("rt"),
        threads=scenario.threads,
    )
    header = [
        f"# scenario: {scenario.name}",
        f"# measurements: {measurements}",
        f"# sectors: {' '.join(names)}",
    ]
    files, note = write_fit(
        result,
        out / f"{scenario.name}_telecover_fit",
        header,
        f"{scenario.name}: telecover fit to {Path(measurements).name}",
    )
    return result, files, [note] if note else []
