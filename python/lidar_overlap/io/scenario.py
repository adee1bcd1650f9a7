"""Scenario files: a lidar system, the ranges and the outputs of one computation, in TOML (SI
units).

A scenario has the top-level keys ``name``, ``description`` and the sections ``[beam]``,
``[telescope]``, ``[detector]``, ``[ranges]`` (required), ``[run]``, ``[output]``, ``[turbulence]``
and ``[fit_bounds]`` (optional); see ``examples/scenarios/table1.toml`` and
``table1_turbulence.toml``. ``[turbulence]`` holds the keys of :class:`lidar_overlap.Turbulence`
(``cn2`` a number or ``"hv57"``, ``elevation``, ...) and the draws' of
:class:`lidar_overlap.Turbulent` (``realizations``, ``seed``, ``screens``, ``paths``,
``receiver_fields``) around the ``[run]`` method. ``[fit_bounds]`` holds the system's
``fit_bounds``, one ``"path" = [low, high]`` per parameter path (SI units; ``"beam.offset[0]"``
quoted, a path without an index may be written bare: ``beam.divergence = [5e-5, 1e-3]``). Every
error is a :class:`ScenarioError` (a ValueError) that names the file, the section and the key, and
says what is valid. ``method = "auto"`` in ``[run]`` is :class:`lidar_overlap.Auto` at the
``[run]`` tolerance: the cheapest model whose error fits it
(Fourier optics for a beam that is not Gaussian).

A scenario is read as untrusted input: the file must be UTF-8 TOML of at most 10 MB, every number
finite, every integer within the bounds of :data:`INTEGER_LIMITS` and at most :data:`MAX_RANGES`
ranges, so that no file can ask for unbounded work or memory before the library's own checks of the
physics.

A scenario is planned once (:meth:`Scenario.plan`, :func:`lidar_overlap.plan`) and the plan run in
chunks of ranges for the progress bar: auto decides for the whole curve, and nothing is computed
twice. Through turbulence the plan runs whole (its draws are made range after range).
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Dict, Optional

import numpy as np

from .. import _checks, _reading
from ..forward.compute import run
from ..forward.methods import Method, Turbulent, from_shortcuts
from ..forward.planning import Plan, plan
from ..forward.result import OverlapResult
from ..model.field_beam import FieldBeam
from ..model.presets import paper_table1
from ..model.system import LidarSystem
from ..model.turbulence import Turbulence
from .scenario_schema import (
    MAX_FILE_BYTES,
    MAX_NAME_LENGTH,
    MAX_RANGES,  # noqa: F401  (re-exported: the docstring's bound)
    METHODS,
    OUTPUTS,
    SCHEMA,
    TOP_KEYS,
    TURBULENCE_PROFILE_KEYS,
    ScenarioError,
    build,
    checked_keys,
    choice,
    fit_bounds_table,
    prefixed,
    require,
    short,
)
from .scenario_sections import (
    beam_from_table,
    detector_from_table,
    ranges_from_table,
    telescope_from_table,
)

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


@dataclass(eq=False)
class Scenario:
    """One computation: ``lo.overlap(system, ranges, method, **options)`` and the files to write.

    ``method`` is ``"rt"``, ``"fo"`` or ``"auto"``; ``options`` the other ``[run]`` keys (keyword
    arguments of :func:`lidar_overlap.overlap`); ``outputs`` maps csv/netcdf/plot/scene to
    booleans."""

    name: str
    description: str
    system: LidarSystem
    ranges: np.ndarray
    method: str = "auto"
    options: Dict[str, Any] = field(default_factory=dict)
    turbulence: Dict[str, Any] = field(default_factory=dict)
    outputs: Dict[str, bool] = field(default_factory=lambda: dict.fromkeys(OUTPUTS, True))
    source: str = "<scenario>"

    def resolved_method(self, method: Optional[str] = None) -> str:
        """``method`` (default: the scenario's) for ``lo.overlap``, checked."""
        return choice(f"{self.source}: [run]", "method", method or self.method, METHODS)

    @property
    def threads(self) -> int:
        """The ``[run]`` threads (0: all cores)."""
        return int(self.options.get("threads", 0))

    def method_object(self, method: Optional[str] = None) -> Method:
        """The method object of ``[run]`` (its method, or ``method`` given instead, with the
        options that apply to it: tolerance, beam_grid, ...): the one place a scenario's ``[run]``
        table becomes a method; library errors become :class:`ScenarioError`."""
        options = {k: v for k, v in self.options.items() if k != "threads"}
        try:
            base = from_shortcuts(self.resolved_method(method), **options)
        except ValueError as exc:
            raise self._library_error(exc, 0) from None
        if not self.turbulence:
            return base
        given = self.turbulence
        profile = {k: v for k, v in given.items() if k in TURBULENCE_PROFILE_KEYS}
        draws = {k: v for k, v in given.items() if k not in TURBULENCE_PROFILE_KEYS}
        atmosphere = build(self.source, "turbulence", Turbulence, **profile)
        return build(self.source, "turbulence", Turbulent, atmosphere, base, **draws)

    def plan(self, method: Optional[str] = None) -> Plan:
        """The :class:`lidar_overlap.Plan` of this scenario with ``method`` (default: the
        scenario's); library errors become :class:`ScenarioError`."""
        model = self.method_object(method)
        try:
            return plan(self.system, self.ranges, model, threads=self.threads)
        except ValueError as exc:
            raise self._library_error(exc, 0) from None

    def model(self, method: Optional[str] = None) -> str:
        """``"rt"`` or ``"fo"``: the model ``method`` (default: the scenario's) computes with
        (auto's choice)."""
        return self.plan(method).method

    def compute(
        self,
        method: Optional[str] = None,
        chunk: Optional[int] = None,
        callback: Optional[Callable[[int], None]] = None,
        plan: Optional[Plan] = None,
    ) -> OverlapResult:
        """The scenario's curve: its ``plan`` (default: :meth:`plan` of ``method``) run over the
        ranges in chunks (ranges are independent and the plan's decisions hold for all: the same
        result as one call), calling ``callback(number_done)`` after each; library errors become
        :class:`ScenarioError`."""
        p = plan if plan is not None else self.plan(method)
        z = self.ranges
        if p.turbulence is not None:  # one run: the draws are made range after range
            try:
                result = run(p)
            except ValueError as exc:
                raise self._library_error(exc, 0) from None
            if callback is not None:
                callback(z.size)
            return result
        if chunk is None:
            threads = self.options.get("threads") or os.cpu_count() or 1
            chunk = (
                max(threads, math.ceil(z.size / 100))
                if p.method == "fo"
                else max(50, math.ceil(z.size / 20))
            )
        parts = []
        for start in range(0, z.size, chunk):
            try:
                parts.append(run(p.subset(slice(start, start + chunk))))
            except ValueError as exc:
                raise self._library_error(exc, start) from None
            if callback is not None:
                callback(min(start + chunk, z.size))
        return dataclasses.replace(
            parts[0],
            ranges=z.copy(),
            overlap=np.concatenate([q.overlap for q in parts]),
            error_estimate=np.concatenate([q.error_estimate for q in parts]),
        )

    def _library_error(self, exc: ValueError, start: int) -> ScenarioError:
        """The library's ValueError about ranges ``start``, ... as a ScenarioError naming the file,
        its section and the index in the whole grid."""
        if isinstance(exc, _checks.ParameterError) and start:
            exc = _checks.reindexed(exc, start)
        parameter = exc.parameter if isinstance(exc, _checks.ParameterError) else ""
        section = "ranges" if parameter.split("[", 1)[0] == "ranges" else "run"
        return ScenarioError(prefixed(self.source, section, exc))


def load_scenario(path) -> Scenario:
    """Read a scenario TOML file; raises :class:`ScenarioError` (a ValueError) naming the bad
    key."""
    path = Path(path)
    source = path.name
    try:
        raw = _reading.read_bytes(
            path, MAX_FILE_BYTES, "the scenario", "a scenario (TOML), which needs a few kB"
        )
    except ValueError as exc:
        raise ScenarioError(str(exc)) from None
    raw = raw[len(_reading.BOM) :] if raw.startswith(_reading.BOM) else raw  # some editors add it
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise ScenarioError(
            f"{source}: not a TOML file: byte {exc.start} (0x{raw[exc.start]:02x}) is not UTF-8 "
            "text"
        ) from None
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(f"{source}: invalid TOML: {exc}") from None
    except RecursionError:
        raise ScenarioError(f"{source}: invalid TOML: arrays or tables nested too deeply") from None
    data.setdefault("name", path.stem)
    return scenario_from_dict(data, source)


def scenario_from_dict(data: Dict[str, Any], source: str = "<scenario>") -> Scenario:
    """Build a :class:`Scenario` from the parsed TOML tables (same checks as
    :func:`load_scenario`)."""
    checked_keys(source, None, data, TOP_KEYS)
    for section in ("beam", "telescope", "detector", "ranges"):
        if section not in data:
            raise ScenarioError(
                f"{source}: missing section [{section}] (required: [beam], [telescope], "
                "[detector], [ranges]; optional: [run], [output], [turbulence], [fit_bounds])"
            )
    require(f"{source}:", data, ("name",))
    name = data["name"]
    if not re.fullmatch(r"[A-Za-z0-9][A-Za-z0-9_.+-]*", name) or len(name) > MAX_NAME_LENGTH:
        raise ScenarioError(
            f"{source}: name = {short(name)} is invalid: expected 1 to {MAX_NAME_LENGTH} letters, "
            "digits and _ . + - (it names the output files)"
        )
    telescope = telescope_from_table(source, data["telescope"])
    system = build(
        source,
        None,
        LidarSystem,
        beam=beam_from_table(source, data["beam"]),
        telescope=telescope,
        detector=detector_from_table(source, data["detector"], telescope),
        fit_bounds=fit_bounds_table(source, data.get("fit_bounds", {})),
    )
    run = dict(checked_keys(source, "run", data.get("run", {}), SCHEMA["run"]))
    method = choice(f"{source}: [run]", "method", run.pop("method", "auto"), METHODS)
    outputs = dict.fromkeys(OUTPUTS, True)
    outputs.update(checked_keys(source, "output", data.get("output", {}), SCHEMA["output"]))
    scenario = Scenario(
        name=name,
        description=data.get("description", ""),
        system=system,
        ranges=ranges_from_table(source, data["ranges"]),
        method=method,
        options=run,
        turbulence=dict(
            checked_keys(source, "turbulence", data.get("turbulence", {}), SCHEMA["turbulence"])
        ),
        outputs=outputs,
        source=source,
    )
    if isinstance(system.beam, FieldBeam) and method == "rt":
        raise ScenarioError(
            f"{source}: [run] method = 'rt' is invalid for a {data['beam'].get('type')} beam: ray "
            "tracing models Gaussian beams only; expected 'fo' or 'auto'"
        )
    return scenario


# -------------------------------------------------------------------------------------------------
# built-in: the paper's Table 1 (lidar_overlap.paper_table1, its one definition) and two variants
TABLE1_RANGES = np.geomspace(5.0, 1000.0, 200)


def table1_scenarios() -> list:
    """The paper's Table 1 scenario (as ``examples/scenarios/table1.toml``: 200 ranges from 5 to
    1000 m, ray tracing) and its variants with a central obstruction r_obs = 20 mm and a detector
    defocus of 5 mm."""
    variants = (
        (
            "table1",
            "Mono-axial lidar of the paper's Table 1: f = 1 m, D = 150 mm, FFOV 0.9 mrad, w0 = 1 "
            "mm, 355 nm",
            paper_table1(),
        ),
        (
            "table1_obstruction_20mm",
            "Table 1 with a central obstruction r_obs = 20 mm, 0.7 m before the aperture",
            paper_table1(obstruction_radius=0.02),
        ),
        (
            "table1_defocus_5mm",
            "Table 1 with the detector 5 mm behind the focal plane",
            paper_table1(defocus=5e-3),
        ),
    )
    return [
        Scenario(name, description, system, TABLE1_RANGES.copy(), "rt", source=f"<built-in {name}>")
        for name, description, system in variants
    ]
