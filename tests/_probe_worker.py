"""Worker process of the hostile-input probes: builds one call from a plain description, runs it,
and judges the outcome against the input contract.

The contract: every public entry point ends either in a ValueError or TypeError whose message names
one of the parameters the caller set, or in a result whose numbers are finite, with every overlap in
[0, 1]. Warnings are allowed. Anything else (another exception type, a crash, a hang, a NaN or
out-of-range number) breaks it.

A probe is a :class:`Call` tree of plain values (floats, ints, strings, tuples, dicts, numpy
arrays), so it pickles small and reads back as the Python expression that reproduces it (see
``_probe_runner``). The worker reads length-prefixed pickles on stdin and answers on a private copy
of its stdout; its own fd 1 is pointed at stderr so that anything the library prints cannot corrupt
the protocol.

Run as ``python -c "import _probe_worker; _probe_worker.serve()"`` with this directory on sys.path.
"""

from __future__ import annotations

import inspect
import math
import os
import pickle
import re
import struct
import sys
import time
import traceback
import warnings
from dataclasses import dataclass, field
from typing import Any

#: Address-space cap of the worker (bytes): a grid the library fails to refuse must fail fast with
#: std::bad_alloc instead of taking the machine's memory.
DEFAULT_MEMORY_LIMIT = 6 << 30

#: Verdicts; "error" and "ok" keep the contract, the others break it.
CLEAN_ERROR, FINITE = "error", "ok"
BAD_ERROR, SILENT_WRONG, CRASH, HANG = "bad_error", "silent_wrong", "crash", "hang"

#: Exception types a clean refusal may have.
CLEAN_TYPES = (ValueError, TypeError)
#: Text of pybind11's argument-mismatch TypeError, which lists C++ signatures instead of naming a
#: parameter.
SIGNATURE_DUMP = "incompatible function arguments"
#: Path quantities whose exact value is +inf where a path holds no turbulence (Cn² = 0 or zero
#: length): the Fried parameter and the isoplanatic angle.
UNBOUNDED_WITHOUT_TURBULENCE = ("fried_parameter", "isoplanatic_angle")


@dataclass(frozen=True)
class Call:
    """``fn(*args, **kwargs)``: ``fn`` is a dotted name in ``lidar_overlap`` ("overlap",
    "Detector.from_fov"), in numpy ("np.full"), or an :class:`Attr` of another node."""

    fn: Any
    args: tuple = ()
    kwargs: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Attr:
    """Attribute ``name`` of the object ``node`` builds (a method to call on it)."""

    node: Any
    name: str


def call(fn, *args, **kwargs) -> Call:
    return Call(fn, tuple(args), dict(kwargs))


# ------------------------------------------------------------------------------------------
# building
def _resolve(fn, names: set):
    import numpy as np

    import lidar_overlap as lo

    if isinstance(fn, Attr):
        return getattr(_build(fn.node, names), fn.name)
    root, _, rest = fn.partition(".") if _is_numpy(fn) else ("lo", "", fn)
    obj = np if root == "np" else lo
    for part in rest.split("."):
        obj = getattr(obj, part)
    return obj


def _is_numpy(fn) -> bool:
    return isinstance(fn, str) and fn.startswith("np.")


def _bound_names(fn, args, kwargs) -> set:
    """Names of the parameters a call sets, positional ones included where the signature is
    known."""
    names = set(kwargs)
    try:
        names |= set(inspect.signature(fn).bind_partial(*args, **kwargs).arguments)
    except (TypeError, ValueError):
        pass
    return names


def _build(node, names: set):
    """The object ``node`` describes; ``names`` collects every parameter name set along the way."""
    if isinstance(node, Call):
        fn = _resolve(node.fn, names)
        args = tuple(_build(a, names) for a in node.args)
        kwargs = {k: _build(v, names) for k, v in node.kwargs.items()}
        if not _is_numpy(node.fn):  # numpy builds test data; its parameters are not the library's
            names |= _bound_names(fn, args, kwargs)
        if isinstance(node.fn, Attr):
            names.add(node.fn.name)
        return fn(*args, **kwargs)
    if isinstance(node, tuple):
        return tuple(_build(v, names) for v in node)
    if isinstance(node, list):
        return [_build(v, names) for v in node]
    if isinstance(node, dict):
        return {k: _build(v, names) for k, v in node.items()}
    return node


def entry_name(node) -> str:
    """Short name of the outermost call, the entry point a probe exercises ("overlap",
    "Turbulence.rytov_variance", "overlap.full_overlap_range")."""
    fn = node.fn
    if isinstance(fn, Attr):
        inner = fn.node.fn if isinstance(fn.node, Call) and isinstance(fn.node.fn, str) else "?"
        return f"{inner}.{fn.name}"
    return fn


# ------------------------------------------------------------------------------------------ judging
def names_a_parameter(message: str, names) -> bool:
    """True when ``message`` names one of ``names`` as a word ("beam.wavelength" and "ranges[2]"
    name "wavelength" and "ranges"; "wavelengths" names neither)."""
    return any(
        re.search(rf"(?<![A-Za-z0-9_]){re.escape(n)}(?![A-Za-z0-9_])", message) for n in names
    )


def judge_exception(exc: BaseException, names) -> tuple:
    message = str(exc)
    kind = type(exc).__name__
    if isinstance(exc, CLEAN_TYPES):  # a subclass (lo.ParameterError) is the refusal its base is
        kind = next(t.__name__ for t in CLEAN_TYPES if isinstance(exc, t))
    else:
        return (
            BAD_ERROR,
            kind,
            message,
            f"{kind} is not a clean refusal (expected ValueError or TypeError)",
        )
    if SIGNATURE_DUMP in message:
        return (
            BAD_ERROR,
            kind,
            message,
            "a pybind11 signature dump instead of a message naming the parameter",
        )
    if not names_a_parameter(message, names):
        return (
            BAD_ERROR,
            kind,
            message,
            f"the message names none of the parameters set: {sorted(names)}",
        )
    return CLEAN_ERROR, kind, message, ""


def _finite_array(name, values, problems, low=None, high=None):
    import numpy as np

    arr = np.asarray(values)
    if arr.dtype == object or not np.issubdtype(arr.dtype, np.number):
        problems.append(f"{name} is not numeric ({arr.dtype})")
        return
    if not np.all(np.isfinite(arr)):
        problems.append(f"{name} holds {int(np.sum(~np.isfinite(arr)))} non-finite value(s)")
        return
    if low is not None and arr.size and (arr.min() < low or arr.max() > high):
        problems.append(
            f"{name} spans [{arr.min():.17g}, {arr.max():.17g}], outside [{low}, {high}]"
        )


def _finite_number(name, value, problems, low=-math.inf, high=math.inf, allow_nan=False):
    if not isinstance(value, (int, float)) and not hasattr(value, "__float__"):
        problems.append(f"{name} = {value!r} is not a number")
        return
    v = float(value)
    if math.isnan(v) and allow_nan:
        return
    if not math.isfinite(v) or not low <= v <= high:
        problems.append(f"{name} = {v!r} is not a finite number in [{low}, {high}]")


def judge_result(result, node, built) -> tuple:
    """(problems, summary) of a returned value: what breaks the contract, and numbers to report."""
    import numpy as np

    import lidar_overlap as lo

    problems: list = []
    summary: dict = {"type": type(result).__name__}
    entry = node.fn.name if isinstance(node.fn, Attr) else node.fn
    if isinstance(result, lo.OverlapResult):
        g = np.asarray(result.overlap, dtype=float)
        summary["overlap"] = g.tolist()
        summary["method"] = result.method
        _finite_array("overlap", g, problems, 0.0, 1.0)
        err = np.asarray(result.error_estimate, dtype=float)
        if np.any(np.isinf(err)) or np.any(err < 0):
            problems.append(f"error_estimate = {err.tolist()} holds an infinite or negative value")
        if isinstance(result, lo.TurbulentOverlapResult):
            for name in ("low", "high"):
                _finite_array(name, getattr(result, name), problems, 0.0, 1.0)
            _finite_array("std", result.std, problems, 0.0, 1.0)
    elif isinstance(result, lo.Field):
        _finite_array("field.values", result.values, problems)
        _finite_number("field.spacing", result.spacing, problems, low=5e-324)
        summary["n"], summary["spacing"] = int(result.values.shape[0]), float(result.spacing)
        with np.errstate(
            all="ignore"
        ):  # reported, not judged: spacing² may overflow for a valid field
            summary["power"] = float(
                np.sum(np.abs(result.values) ** 2) * np.float64(result.spacing) ** 2
            )
    elif isinstance(result, lo.FieldBeam):  # FlatTopBeam too
        _finite_array("beam.field.values", result.field.values, problems)
        if isinstance(result, lo.FlatTopBeam):
            _finite_array("far_field", result.far_field, problems)
            _finite_number("efficiency", result.efficiency, problems, 0.0, 1.0 + 1e-9)
    elif isinstance(result, lo.DetectorImage):
        _finite_array("image", result.image, problems)
        if not problems and float(np.sum(result.image)) > 0:
            summary["fraction"] = result.fraction
            _finite_number("fraction", result.fraction, problems, 0.0, 1.0 + 1e-12)
    elif isinstance(result, lo.Plan):
        if result.method not in ("rt", "fo"):
            problems.append(f"decision.method = {result.method!r}")
        fieldbeam = isinstance(getattr(built[0], "beam", None), lo.FieldBeam) if built else False
        _finite_number("rt_model_error", result.rt_model_error, problems, 0.0, allow_nan=fieldbeam)
        summary["method"], summary["fo_path"] = result.method, result.fo_path
    elif isinstance(result, lo.TelecoverResult):
        _finite_array("sectors' overlap", result.overlap, problems, 0.0, 1.0)
        _finite_array("full.overlap", result.full.overlap, problems, 0.0, 1.0)
        dev = np.asarray(
            result.deviation, dtype=float
        )  # NaN is documented where every sector's G is 0
        if np.any(np.isinf(dev)) or np.any(
            np.isnan(dev) & (np.asarray(result.overlap).sum(axis=0) > 0)
        ):
            problems.append("deviation holds an infinite value, or NaN where the sectors see light")
        summary["overlap"] = np.asarray(result.overlap).tolist()
    elif isinstance(result, lo.CorrectedSignal):
        mask = np.asarray(result.mask, dtype=bool)
        for name in ("values", "std"):  # NaN is documented where masked
            _finite_array(name, np.asarray(getattr(result, name), dtype=float)[~mask], problems)
        summary["masked"] = int(mask.sum())
    elif type(result).__name__ == "Dataset":  # alignment maps and sensitivities (xarray)
        for name, var in result.data_vars.items():
            if var.dtype.kind in "biuf":  # units and labels are strings
                low, high = (0.0, 1.0) if name == "overlap" else (None, None)
                _finite_array(name, var.values, problems, low, high)
        summary["variables"] = sorted(result.data_vars)
    elif isinstance(result, lo.GaussianBeam):
        _finite_number("half_angle_divergence", result.half_angle_divergence, problems, 0.0)
    elif isinstance(result, lo.Detector):
        _finite_number("detector.radius", result.radius, problems, 0.0)
    elif isinstance(result, np.ndarray):  # a phase screen, a Zernike polynomial's values
        _finite_array(entry, result, problems)
        summary["shape"] = list(result.shape)
    elif isinstance(result, tuple) and entry == "noll_index":
        if not all(isinstance(v, int) for v in result) or len(result) != 2 or result[0] < 0:
            problems.append(f"noll_index = {result!r} is not a pair (n >= 0, m) of integers")
    elif isinstance(result, (bool, np.bool_)) or result is None:
        problems.append(f"returned {result!r}, not a number or an object of the library")
    elif isinstance(result, (int, float, np.integer, np.floating)):
        v = float(result)
        summary["value"] = v
        if entry == "emitter_coupling":
            _finite_number("coupling", v, problems, 0.0, 1.0)
        elif entry in (
            "full_overlap_range",
            "first_signal_range",
        ):  # NaN is documented: never reached
            _finite_number(entry, v, problems, 0.0, allow_nan=True)
        elif entry == "optimal_focus_range" and v == math.inf and _defocus_is_zero(node, built):
            pass  # documented: inf for defocus 0
        elif entry == "optimal_focus_range":
            _finite_number(entry, v, problems, 0.0)
        elif entry in UNBOUNDED_WITHOUT_TURBULENCE and v == math.inf:
            pass
        else:  # Turbulence methods: r0, variances, radii, angles are all >= 0
            _finite_number(entry, v, problems, 0.0)
    return problems, summary


def _defocus_is_zero(node, built) -> bool:
    defocus = node.kwargs.get("defocus", built[1] if len(built) > 1 else None)
    return isinstance(defocus, (int, float)) and not isinstance(defocus, bool) and defocus == 0


# ------------------------------------------------------------------------------------------ running
def run_probe(node) -> dict:
    """Build and run ``node`` with every warning recorded (never raised), and judge the outcome.
    ``warnings`` holds those of the outermost call alone, ``build_warnings`` those of building its
    arguments."""
    names: set = set()
    start = time.perf_counter()
    building: list = []
    calling: list = []
    try:
        if not isinstance(node, Call):
            raise TypeError("a probe is a Call")
        with warnings.catch_warnings(record=True) as building:
            warnings.simplefilter("always")
            fn = _resolve(node.fn, names)
            if isinstance(node.fn, Attr):
                names.add(node.fn.name)
            built = tuple(_build(a, names) for a in node.args)
            kwargs = {k: _build(v, names) for k, v in node.kwargs.items()}
            names |= _bound_names(fn, built, kwargs)
        with warnings.catch_warnings(record=True) as calling:
            warnings.simplefilter("always")
            result = fn(*built, **kwargs)
    except BaseException as exc:  # noqa: BLE001 - every exception is an outcome to judge
        if isinstance(exc, (KeyboardInterrupt, SystemExit)):
            raise
        verdict, kind, message, why = judge_exception(exc, names)
        outcome = {
            "verdict": verdict,
            "type": kind,
            "message": message[:2000],
            "why": why,
            "traceback": traceback.format_exc(limit=-4)[-3000:] if verdict != CLEAN_ERROR else "",
        }
    else:
        try:
            problems, summary = judge_result(result, node, built)
        except Exception as exc:  # noqa: BLE001 - a result that cannot even be inspected is wrong
            problems, summary = [f"inspecting the result raised {type(exc).__name__}: {exc}"], {}
        outcome = {
            "verdict": SILENT_WRONG if problems else FINITE,
            "why": "; ".join(problems),
            "summary": summary,
        }
    outcome.update(
        seconds=time.perf_counter() - start,
        warnings=_warning_list(calling),
        build_warnings=_warning_list(building),
    )
    return outcome


def _warning_list(caught) -> list:
    return [
        (w.category.__name__, issubclass(w.category, RuntimeWarning), str(w.message)[:300])
        for w in caught
    ]


def _read_exact(stream, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = stream.read(n - len(data))
        if not chunk:
            raise EOFError
        data += chunk
    return data


def serve() -> None:
    """Answer probes until stdin closes: each request and reply is a 4-byte length and a pickle."""
    import resource

    limit = int(os.environ.get("LIDAR_OVERLAP_PROBE_MEMORY", DEFAULT_MEMORY_LIMIT))
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
    reply = os.fdopen(os.dup(1), "wb", buffering=0)
    os.dup2(2, 1)  # whatever the library prints goes to stderr, not into the protocol
    sys.stdout = sys.stderr
    requests = sys.stdin.buffer
    import lidar_overlap  # noqa: F401 - imported once, before the first probe's clock starts

    reply.write(struct.pack("<I", 0))  # ready
    while True:
        try:
            (size,) = struct.unpack("<I", _read_exact(requests, 4))
            node = pickle.loads(_read_exact(requests, size))
        except EOFError:
            return
        answer = pickle.dumps(run_probe(node))
        reply.write(struct.pack("<I", len(answer)) + answer)
