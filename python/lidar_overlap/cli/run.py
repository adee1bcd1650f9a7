"""``lidar-overlap run`` and ``demo``: a scenario computed, then its files written (CSV, NetCDF,
the plot, the 3-D scene), each only once the computation has succeeded and each under a temporary
name until complete; and the summary printed."""

from __future__ import annotations

import importlib.util
import math
import os
import time
from pathlib import Path
from typing import List, Optional

import numpy as np

from .. import _files
from ..io.scenario import Scenario
from ..views.scene import save_scene
from .output import noted, one_line, printed_warnings, progress


def run_one(scenario: Scenario, out: Path, method: Optional[str], quiet: bool):
    with printed_warnings():
        return compute_and_write(scenario, out, method, quiet)


def compute_and_write(scenario: Scenario, out: Path, method: Optional[str], quiet: bool):
    start = time.perf_counter()
    plan = scenario.plan(method)  # decided once: auto's estimate is not made again to run it
    n = scenario.ranges.size
    slow = n > 50 or plan.method == "fo"
    show, close = progress(scenario.name, n) if slow and not quiet else (None, None)
    done = False
    try:
        result = scenario.compute(plan=plan, callback=show)
        done = True
    finally:
        if close is not None:
            close(done)
    elapsed = time.perf_counter() - start
    out.mkdir(parents=True, exist_ok=True)
    stem, attrs = (
        out / scenario.name,
        # the description may span lines in the TOML file; a header value is one line
        {"scenario": scenario.name, "description": " ".join(scenario.description.split())},
    )
    files, want = [], scenario.outputs
    if want.get("csv"):
        result.to_csv(f"{stem}.csv", attrs)
        files.append(f"{stem}.csv")
    if want.get("netcdf"):
        try:
            result.to_netcdf(
                f"{stem}.nc", {"title": f"Lidar overlap function G(z): {scenario.name}", **attrs}
            )
            files.append(f"{stem}.nc")
        except ImportError as exc:
            noted((None, f"{stem}.nc not written: {exc}"))
    if want.get("plot"):
        files.append(
            noted(
                plot_file([(scenario, result)], Path(f"{stem}_overlap.png"), scenario.description)
            )
        )
    if want.get("scene"):
        files.append(noted(scene_file(scenario, result, Path(f"{stem}_scene.png"))))
    summary(scenario, result, elapsed, [f for f in files if f])
    return scenario, result


def summary(scenario: Scenario, result, elapsed: float, files: List[str]) -> None:
    def at(z: float, rule: str) -> str:
        return f"{z:.4g} m ({rule})" if math.isfinite(z) else f"none ({rule} nowhere on the grid)"

    tolerance = f" (tolerance {result.tolerance:g})" if math.isfinite(result.tolerance) else ""
    z = result.ranges
    print(
        f"{scenario.name}: {one_line(scenario.description)}"
        if scenario.description
        else scenario.name
    )
    print(f"  method        {result.method}{tolerance}")
    print(
        f"  ranges        {z.size} from {z[0]:.4g} m to {z[-1]:.4g} m; max G = "
        f"{result.overlap.max():.4g}"
    )
    print(f"  full overlap  {at(result.full_overlap_range(), 'G >= 0.99 max G')}")
    print(f"  first signal  {at(result.first_signal_range(), 'G >= 1e-3')}")
    amplification = getattr(result, "amplification", None)
    if amplification is not None and np.isfinite(amplification).any():
        print(
            f"  amplification {np.nanmin(amplification):.4g} to {np.nanmax(amplification):.4g} "
            "(mean G over that of uncorrelated paths)"
        )
    print(f"  time          {elapsed:.3g} s")
    print(f"  files         {', '.join(files) if files else 'none'}")


def plot_file(runs, path: Path, title: str):
    """Plot G(z) of each (scenario, result) with its full-overlap and first-signal ranges; returns
    (path, None) or (None, note)."""
    try:
        from matplotlib.figure import Figure
    except ImportError:
        return (
            None,
            f"{path} not written: plotting needs matplotlib: pip install 'lidar-overlap[plot]'",
        )
    fig = Figure(figsize=(7.0, 4.4), constrained_layout=True)
    ax = fig.add_subplot()
    for scenario, result in runs:
        label = f"{scenario.name} ({result.method})" if len(runs) > 1 else result.method
        result.plot(ax=ax, label=label)
        color = ax.lines[-1].get_color()
        for z, style, what in (
            (result.full_overlap_range(), "--", "full overlap"),
            (result.first_signal_range(), ":", "first signal"),
        ):
            if math.isfinite(z):
                ax.plot([], [], style, color=color, lw=0.8, label=f"{what}: {z:.4g} m")
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(title, fontsize=9)
    with _files.replacing_path(path) as temporary:  # keeps the .png suffix, which sets the format
        fig.savefig(temporary, dpi=120)
    return str(path), None


def scene_file(scenario: Scenario, result, path: Path):
    """The 3-D scene (:func:`lidar_overlap.save_scene`) when pyvista is installed."""
    if importlib.util.find_spec("pyvista") is None:
        return (
            None,
            f"{path} not written: the 3-D scene needs pyvista: pip install 'lidar-overlap[viz]'",
        )
    try:
        with _files.replacing_path(path) as temporary:
            save_scene(scenario.system, str(temporary), result=result)
            if os.path.getsize(temporary) == 0:
                raise _NothingWritten
    except _NothingWritten:
        return None, f"{path} not written by save_scene"
    except OSError:
        raise  # a file error (a full disk) fails the run like any other file
    except Exception as exc:  # an optional picture must not lose the computed results
        return None, f"{path} not written: {type(exc).__name__}: {exc}"
    return str(path), None


class _NothingWritten(Exception):
    pass
