"""Command line: ``lidar-overlap run SCENARIO.toml``, ``lidar-overlap demo`` (see
:mod:`lidar_overlap.io.scenario`), ``lidar-overlap fit SCENARIO.toml MEASUREMENTS.csv --free PATH
...`` (see :mod:`lidar_overlap.analysis.fit`) and ``lidar-overlap telecover SCENARIO.toml
[--measurements CSV --free PATH ...]`` (see :mod:`lidar_overlap.analysis.telecover`) and
``lidar-overlap view SCENARIO.toml`` (the interactive page: :mod:`lidar_overlap.views.app`).

Exit codes: 0 success; 1 any failure: a scenario that cannot be used, a computation the library
refuses, a file that cannot be read or written; 2 a command-line syntax error (argparse); 130
interrupted (Ctrl-C). A failure prints exactly one line on stderr, ``lidar-overlap: error: ...``,
naming the file, the section and the key where it can, and never a traceback.

Nothing is written before the computation has succeeded, and every file (CSV, NetCDF, PNG) is
written under a temporary name beside its final one and renamed only when complete, so a failure (a
full disk, Ctrl-C) never leaves a partial file. Results are checked on construction
(:class:`OverlapResult`), so a curve with a NaN or out-of-range G is a failure, not a file. Warnings
are printed, one line each, once the scenario has succeeded.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import sys
import time
import warnings
from contextlib import contextmanager
from pathlib import Path
from typing import List, Optional

import numpy as np

from .. import _files
from .._core import __version__
from ..forward.methods import RT
from ..io.scenario import METHODS, Scenario, load_scenario, table1_scenarios
from ..views.app import view
from ..views.scene import save_scene
from . import fit as fit_command
from . import telecover as telecover_command

PROG = "lidar-overlap"
#: The longest error line printed (a message quoting a large value is cut there).
MAX_MESSAGE = 1000


class _UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line instead of usage + message
        raise _UsageError(f"{message} (see {self.prog} --help)")


def _parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog=PROG, description="Overlap function G(z) of an atmospheric lidar from a scenario file."
    )
    parser.add_argument("--version", action="version", version=f"{PROG} {__version__}")
    sub = parser.add_subparsers(
        dest="command", required=True, metavar="{run,demo,fit,telecover,view}"
    )
    run = sub.add_parser(
        "run",
        help="compute one scenario (TOML) and write its files",
        description="Compute a scenario and write <name>.csv, <name>.nc, <name>_overlap.png and "
        "<name>_scene.png, as its [output] section asks.",
    )
    run.add_argument("scenario", help="scenario file (TOML), e.g. examples/scenarios/table1.toml")
    demo = sub.add_parser(
        "demo",
        help="the paper's Table 1 lidar, with r_obs = 20 mm and with 5 mm defocus",
        description="Compute the paper's Table 1 scenario and its obstruction (20 mm) and defocus "
        "(5 mm) variants, built in, and write their files.",
    )
    fit = sub.add_parser(
        "fit",
        help="fit system parameters of a scenario to a measured overlap (CSV)",
        description="Fit the --free parameters of the scenario's system (the start) to the "
        "measured G in a CSV with the header range_m,overlap[,sigma]; write <name>_fit.csv and "
        "<name>_fit.png and print the summary.",
    )
    fit.add_argument(
        "scenario", help="scenario file (TOML): the starting system and the [run] model"
    )
    fit.add_argument(
        "measurements", type=Path, help="CSV file with the header range_m,overlap[,sigma]"
    )
    fit.add_argument(
        "--free",
        nargs="+",
        required=True,
        metavar="PATH",
        help="parameters to fit, e.g. beam.tilt detector.defocus (beam.tilt: both components)",
    )
    fit.add_argument(
        "--normalize",
        nargs=2,
        type=float,
        metavar=("Z_LOW", "Z_HIGH"),
        help="relative data: divide the model and the data each by their mean over Z_LOW..Z_HIGH "
        "(m), e.g. an overlap curve normalised to 1 in the far range",
    )
    tc = sub.add_parser(
        "telecover",
        help="the telecover test of a scenario, or a fit to measured deviations",
        description="Compute the telecover test of the scenario's system at its ranges and write "
        "<name>_telecover.csv and .png; with --measurements (CSV: range_m, one deviation column "
        "per sector, optional sigma), fit the --free parameters to it and write "
        "<name>_telecover_fit.csv and .png.",
    )
    tc.add_argument("scenario", help="scenario file (TOML): the system, ranges and [run] model")
    tc.add_argument(
        "--sectors",
        type=_sectors,
        default="quadrants",
        metavar="quadrants|N",
        help="the quadrants north, east, south, west (default) or N equal sectors from +x",
    )
    tc.add_argument(
        "--measurements", type=Path, help="CSV with the header range_m,<sector>,...[,sigma]"
    )
    tc.add_argument(
        "--free",
        nargs="+",
        metavar="PATH",
        help="parameters to fit with --measurements, e.g. beam.tilt",
    )
    view = sub.add_parser(
        "view",
        help="the scenario's system as an interactive page in the browser",
        description="Serve the scenario's system on localhost: its 3-D scene, sliders for the "
        "alignment and receiver, G(z) by ray tracing (200 ranges over the scenario's span), the "
        "detector image; the save button writes <name>.toml and .csv. Needs pip install "
        "'lidar-overlap[app]'.",
    )
    view.add_argument("scenario", help="scenario file (TOML) with a Gaussian beam")
    view.add_argument(
        "--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one, printed)"
    )
    view.add_argument(
        "--telecover", action="store_true", help="show the quadrants' telecover deviations"
    )
    view.add_argument("--no-browser", action="store_true", help="do not open the system browser")
    view.add_argument(
        "--timeout",
        type=float,
        default=0.0,
        help="stop when no page has been connected for this many seconds (default 0: never)",
    )
    view.add_argument("--out", type=Path, help="where the save button writes (default: ./<name>/)")
    for p, default in (
        (run, "./<name>/"),
        (demo, "./lidar-overlap-demo/"),
        (fit, "./<name>/"),
        (tc, "./<name>/"),
    ):
        p.add_argument("--out", type=Path, help=f"output directory (default: {default})")
        p.add_argument(
            "--method",
            choices=METHODS,
            help="override [run] method; auto: the cheapest model within the [run] tolerance",
        )
        if p is not fit:
            p.add_argument(
                "--quiet",
                action="store_true",
                help="no progress bar" if p is not tc else "no summary",
            )
    return parser


def main(argv: Optional[List[str]] = None) -> int:
    """Run the command line; returns the exit code."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # --help, --version
        return exc.code if isinstance(exc.code, int) else 0
    except _UsageError as exc:
        return _fail(str(exc), 2)
    try:
        if args.command == "view":
            return _view(args)
        if args.command == "fit":
            return _fit(load_scenario(args.scenario), args)
        if args.command == "telecover":
            return _telecover(args)
        if args.command == "run":
            scenario = load_scenario(args.scenario)
            _run_one(scenario, args.out or Path(scenario.name), args.method, args.quiet)
        else:
            out = args.out or Path("lidar-overlap-demo")
            results = [_run_one(s, out, args.method, args.quiet) for s in table1_scenarios()]
            with _printed_warnings():
                combined = _note(
                    _plot_file(
                        results, out / "table1_variants_overlap.png", "Table 1 and its variants"
                    )
                )
            print(
                f"demo: {len(results)} scenarios written to {out}"
                + (f"; compared in {combined}" if combined else "")
            )
    except KeyboardInterrupt:
        return _fail("interrupted", 130)
    except (
        ValueError
    ) as exc:  # ScenarioError, and the library's refusals (one line naming the parameter)
        return _fail(str(exc), 1)
    except OSError as exc:
        return _fail(f"cannot write {exc.filename or 'the output'}: {exc.strerror or exc}", 1)
    except MemoryError:
        return _fail("out of memory: ask for fewer ranges or smaller grids", 1)
    except Exception as exc:  # a defect: still one line and a failure, never a traceback
        return _fail(
            f"internal error: {type(exc).__name__}: {exc} (please report it with the scenario)", 1
        )
    return 0


def _fit(scenario: Scenario, args) -> int:
    try:
        with _printed_warnings():  # printed only if the fit succeeds
            result, files, note = fit_command.fit_scenario(
                scenario,
                args.measurements,
                args.free,
                args.out or Path(scenario.name),
                args.method,
                normalize=None if args.normalize is None else tuple(args.normalize),
            )
            _note((None, note))
    except (RuntimeError, ImportError) as exc:  # not converged; scipy missing
        return _fail(str(exc), 1)
    print(f"{scenario.name}: {result.summary()}")
    print(f"  files         {', '.join(files)}")
    return 0


def _view(args) -> int:
    """``lidar-overlap view``: the scenario's system served as the interactive page."""
    scenario = load_scenario(args.scenario)
    z = scenario.ranges
    ranges = np.geomspace(z[0], z[-1], 200) if z.size > 1 else z
    tolerance = scenario.options.get("tolerance", RT().tolerance)
    try:
        view(
            scenario.system,
            ranges,
            telecover="quadrants" if args.telecover else None,
            name=scenario.name,
            out=args.out or Path(scenario.name),
            port=args.port,
            open_browser=not args.no_browser,
            timeout=args.timeout,
            tolerance=tolerance,
            block=True,
        )
    except ImportError as exc:
        return _fail(str(exc), 1)
    return 0


def _sectors(text: str):
    try:
        return telecover_command.sectors_argument(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _telecover(args) -> int:
    if (args.measurements is None) != (args.free is None):
        return _fail("telecover: --measurements and --free go together (a fit needs both)", 2)
    if args.measurements is not None and args.method not in (None, "rt"):
        return _fail(
            f"telecover: --method {args.method} is invalid with --measurements: the telecover fit "
            "runs ray tracing (leave --method out)",
            2,
        )
    scenario = load_scenario(args.scenario)
    out = args.out or Path(scenario.name)
    try:
        with _printed_warnings():
            if args.measurements is None:
                result, files, notes = telecover_command.compute(
                    scenario, args.sectors, out, args.method
                )
                lines = telecover_command.summary(scenario.name, result)
            else:
                result, files, notes = telecover_command.fit(
                    scenario, args.sectors, args.measurements, args.free, out
                )
                lines = [f"{scenario.name}: telecover {result.summary()}"]
            for note in notes:
                _note((None, note))
    except (RuntimeError, ImportError) as exc:  # not converged; scipy missing
        return _fail(str(exc), 1)
    if not args.quiet:
        print("\n".join(lines + [f"  files         {', '.join(files)}"]))
    return 0


def _run_one(scenario: Scenario, out: Path, method: Optional[str], quiet: bool):
    with _printed_warnings():
        return _compute_and_write(scenario, out, method, quiet)


def _compute_and_write(scenario: Scenario, out: Path, method: Optional[str], quiet: bool):
    start = time.perf_counter()
    plan = scenario.plan(method)  # decided once: auto's estimate is not made again to run it
    n = scenario.ranges.size
    slow = n > 50 or plan.method == "fo"
    show, close = _progress(scenario.name, n) if slow and not quiet else (None, None)
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
            _note((None, f"{stem}.nc not written: {exc}"))
    if want.get("plot"):
        files.append(
            _note(
                _plot_file([(scenario, result)], Path(f"{stem}_overlap.png"), scenario.description)
            )
        )
    if want.get("scene"):
        files.append(_note(_scene_file(scenario, result, Path(f"{stem}_scene.png"))))
    _summary(scenario, result, elapsed, [f for f in files if f])
    return scenario, result


def _summary(scenario: Scenario, result, elapsed: float, files: List[str]) -> None:
    def at(z: float, rule: str) -> str:
        return f"{z:.4g} m ({rule})" if math.isfinite(z) else f"none ({rule} nowhere on the grid)"

    tolerance = f" (tolerance {result.tolerance:g})" if math.isfinite(result.tolerance) else ""
    z = result.ranges
    print(
        f"{scenario.name}: {_one_line(scenario.description)}"
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
    print(f"  time          {elapsed:.3g} s")
    print(f"  files         {', '.join(files) if files else 'none'}")


def _plot_file(runs, path: Path, title: str):
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


def _scene_file(scenario: Scenario, result, path: Path):
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


def _progress(label: str, total: int):
    """A callback(number_done) drawing a tqdm bar if installed, else a counter on stderr, and its
    closer close(completed), which erases the counter of a failed run so that the error stays the
    only line."""
    try:
        from tqdm import tqdm
    except ImportError:

        def show(done):
            print(f"\r{label}: {done}/{total} ranges", end="", file=sys.stderr, flush=True)

        def close(completed):
            blank = " " * len(f"{label}: {total}/{total} ranges")
            print(
                "" if completed else f"\r{blank}\r",
                end="\n" if completed else "",
                file=sys.stderr,
                flush=True,
            )

        return show, close
    bar = tqdm(total=total, desc=label, unit="range", file=sys.stderr, leave=False)
    return lambda done: bar.update(done - bar.n), lambda completed: bar.close()


class _Note(UserWarning):
    """An output left out (an optional dependency missing), printed as "note: ..." with the
    warnings."""


def _note(written_and_note):
    path, note = written_and_note
    if note:
        warnings.warn(note, _Note)
    return path


@contextmanager
def _printed_warnings():
    """Collect the warnings of a block and print them, one line each and each once, if the block
    succeeds (a failure prints its error alone). Runtime warnings are always shown, whatever filters
    the caller set."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", RuntimeWarning)
        warnings.simplefilter("always", UserWarning)
        yield
    kinds = {_Note: "note"}
    lines = (f"{kinds.get(w.category, 'warning')}: {_one_line(str(w.message))}" for w in caught)
    for line in dict.fromkeys(lines):  # each once, in order
        print(line, file=sys.stderr)


def _fail(message: str, code: int) -> int:
    line = _one_line(str(message))
    if len(line) > MAX_MESSAGE:
        line = f"{line[: MAX_MESSAGE - 3]}..."
    print(f"{PROG}: error: {line}", file=sys.stderr)
    return code


def _one_line(text: str) -> str:
    """``text`` on one line, without control characters (a scenario's text must not drive the
    terminal)."""
    return " ".join("".join(c if c.isprintable() else " " for c in text).split())


if __name__ == "__main__":
    sys.exit(main())
