"""Command line: ``lidar-overlap run SCENARIO.toml``, ``lidar-overlap demo`` (see
:mod:`lidar_overlap.io.scenario`), ``lidar-overlap fit SCENARIO.toml MEASUREMENTS.csv --free PATH
...`` (see :mod:`lidar_overlap.analysis.fitting.fit`) and ``lidar-overlap telecover SCENARIO.toml
[--measurements CSV --free PATH ...]`` (see :mod:`lidar_overlap.analysis.studies.telecover`) and
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
import math
import sys
from pathlib import Path
from typing import List, Optional

import numpy as np

from .. import _reading
from .._core import __version__
from ..forward.methods import RT
from ..io.scenario import METHODS, Scenario, load_scenario, table1_scenarios
from ..model.system import GaussianBeam
from ..views.app import view
from ..views.twin import N_RANGES, N_RANGES_AUTO
from . import fit as fit_command
from . import telecover as telecover_command
from .output import PROG, fail, noted, printed_warnings
from .run import plot_file, run_one


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
        type=_decimal,
        metavar=("Z_LOW", "Z_HIGH"),
        help="relative data: divide the model and the data each by their mean over Z_LOW..Z_HIGH "
        "(m), e.g. an overlap curve normalised to 1 in the far range",
    )
    fit.add_argument(
        "--extinction-bias",
        action="store_true",
        help="with --normalize: also fit the error (1/m) of the extinction the curve's retrieval "
        "assumed, the factor exp(-2 da (z - z_ref)) it leaves in the data",
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
    tc.add_argument(
        "--outside-validity",
        action="store_true",
        help="with --measurements: fit even at ranges outside ray tracing's validity (warned "
        "instead of refused)",
    )
    view = sub.add_parser(
        "view",
        help="the scenario's system as an interactive page in the browser",
        description="Serve the scenario's system on localhost: its 3-D scene, sliders for the "
        "alignment and receiver, G(z) (a Gaussian beam by ray tracing, 200 ranges over the "
        "scenario's span; another beam by the model auto chooses, 40 ranges, computed in the "
        "background), the detector image; the save button writes <name>.toml and .csv. Needs pip "
        "install 'lidar-overlap[app]'.",
    )
    view.add_argument("scenario", help="scenario file (TOML)")
    view.add_argument(
        "--port", type=_port, default=0, help="port on 127.0.0.1 (default: a free one, printed)"
    )
    view.add_argument(
        "--telecover", action="store_true", help="show the quadrants' telecover deviations"
    )
    view.add_argument("--no-browser", action="store_true", help="do not open the system browser")
    view.add_argument(
        "--timeout",
        type=_whole_seconds,
        default=0,
        help="stop when no page has been connected for this many whole seconds (default 0: never)",
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
        return fail(str(exc), 2)
    try:
        if args.command == "view":
            return _view(args)
        if args.command == "fit":
            return _fit(load_scenario(args.scenario), args)
        if args.command == "telecover":
            return _telecover(args)
        if args.command == "run":
            scenario = load_scenario(args.scenario)
            run_one(scenario, args.out or Path(scenario.name), args.method, args.quiet)
        else:
            out = args.out or Path("lidar-overlap-demo")
            results = [run_one(s, out, args.method, args.quiet) for s in table1_scenarios()]
            with printed_warnings():
                combined = noted(
                    plot_file(
                        results, out / "table1_variants_overlap.png", "Table 1 and its variants"
                    )
                )
            print(
                f"demo: {len(results)} scenarios written to {out}"
                + (f"; compared in {combined}" if combined else "")
            )
    except KeyboardInterrupt:
        return fail("interrupted", 130)
    except (
        ValueError
    ) as exc:  # ScenarioError, and the library's refusals (one line naming the parameter)
        return fail(str(exc), 1)
    except OSError as exc:
        return fail(f"cannot write {exc.filename or 'the output'}: {exc.strerror or exc}", 1)
    except MemoryError:
        return fail("out of memory: ask for fewer ranges or smaller grids", 1)
    except Exception as exc:  # a defect: still one line and a failure, never a traceback
        return fail(
            f"internal error: {type(exc).__name__}: {exc} (please report it with the scenario)", 1
        )
    return 0


def _fit(scenario: Scenario, args) -> int:
    try:
        with printed_warnings():  # printed only if the fit succeeds
            result, files, note = fit_command.fit_scenario(
                scenario,
                args.measurements,
                args.free,
                args.out or Path(scenario.name),
                args.method,
                normalize=None if args.normalize is None else tuple(args.normalize),
                extinction_bias=args.extinction_bias,
            )
            noted((None, note))
    except (RuntimeError, ImportError) as exc:  # not converged; scipy missing
        return fail(str(exc), 1)
    print(f"{scenario.name}: {result.summary()}")
    print(f"  files         {', '.join(files)}")
    return 0


def _view(args) -> int:
    """``lidar-overlap view``: the scenario's system served as the interactive page."""
    scenario = load_scenario(args.scenario)
    out = args.out or Path(scenario.name)
    if out.exists() and not out.is_dir():  # checked before serving, not when saving
        return fail(f"view: --out {out} is invalid: expected a directory (it is a file)", 2)
    z = scenario.ranges
    count = N_RANGES if isinstance(scenario.system.beam, GaussianBeam) else N_RANGES_AUTO
    ranges = np.geomspace(z[0], z[-1], count) if z.size > 1 else z
    tolerance = scenario.options.get("tolerance", RT().tolerance)
    try:
        view(
            scenario.system,
            ranges,
            telecover="quadrants" if args.telecover else None,
            name=scenario.name,
            out=out,
            port=args.port,
            open_browser=not args.no_browser,
            timeout=args.timeout,
            tolerance=tolerance,
            block=True,
        )
    except ImportError as exc:
        return fail(str(exc), 1)
    return 0


def _decimal(text: str) -> float:
    """A finite number as the project's files write it (ASCII digits, '.' as decimal point)."""
    value = _reading.number(text)
    if value is None or not math.isfinite(value):
        raise argparse.ArgumentTypeError(
            f"{text!r} is invalid: expected a finite number in ASCII digits with '.' as the "
            "decimal point"
        )
    return value


def _integer_from(text: str, low: int, high: int, what: str) -> int:
    value = _reading.integer(text)
    if value is None or not low <= value <= high:
        raise argparse.ArgumentTypeError(
            f"{text!r} is invalid: expected {what}, an integer from {low} to {high} in ASCII digits"
        )
    return value


def _whole_seconds(text: str) -> int:
    """``view --timeout``: whole seconds (a fraction of a second was never honoured)."""
    return _integer_from(text, 0, 10**7, "whole seconds")


def _port(text: str) -> int:
    return _integer_from(text, 0, 65535, "a port")


def _sectors(text: str):
    try:
        return telecover_command.sectors_argument(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def _telecover(args) -> int:
    if (args.measurements is None) != (args.free is None):
        return fail("telecover: --measurements and --free go together (a fit needs both)", 2)
    if args.measurements is not None and args.method not in (None, "rt"):
        return fail(
            f"telecover: --method {args.method} is invalid with --measurements: the telecover fit "
            "runs ray tracing (leave --method out)",
            2,
        )
    scenario = load_scenario(args.scenario)
    out = args.out or Path(scenario.name)
    try:
        with printed_warnings():
            if args.measurements is None:
                result, files, notes = telecover_command.compute(
                    scenario, args.sectors, out, args.method
                )
                lines = telecover_command.summary(scenario.name, result)
            else:
                result, files, notes = telecover_command.fit(
                    scenario,
                    args.sectors,
                    args.measurements,
                    args.free,
                    out,
                    outside_validity=args.outside_validity,
                )
                lines = [f"{scenario.name}: telecover {result.summary()}"]
            for note in notes:
                noted((None, note))
    except (RuntimeError, ImportError) as exc:  # not converged; scipy missing
        return fail(str(exc), 1)
    if not args.quiet:
        print("\n".join(lines + [f"  files         {', '.join(files)}"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
