"""Flat-top beams: a TEM00 laser through a Gerchberg–Saxton phase plate (paper Section 4C, Figs.
6–7)."""

from __future__ import annotations

from dataclasses import FrozenInstanceError

import numpy as np

from .. import _checks, _core
from .field import Field
from .field_beam import MIN_BEAM_POWER, FieldBeam, Pair


class FlatTopBeam(FieldBeam):
    """A Gaussian beam (waist ``waist_radius``) through a phase plate whose far-field irradiance is
    a uniform disc of full angular diameter ``angular_diameter``, designed with the Gerchberg–Saxton
    (error-reduction) algorithm from the ray-optics plate that maps the Gaussian's enclosed power
    onto a disc's.

    A waist w0 can only be spread, and its far field cannot change faster than its own diffraction
    angle θd = λ/(π w0): the target disc has a soft (Fermi-Dirac) edge of 10–90 % width
    ``edge_width`` (default 1.5 θd). Sharper edges leave ripples on the plateau (``stop ==
    "stagnated"``).

    Parameters
    ----------
    wavelength : m.
    waist_radius : m, 1/e² radius of the laser at the plate (z = 0).
    angular_diameter : rad, full diameter of the far-field disc at half its plateau irradiance; more
        than the TEM00 full divergence 2θd.
    grid : samples per side of the plate (even, >= 64); the far field is sampled every λ/(grid ·
        spacing).
    samples_per_waist : plate sampling, w0 / spacing.
    edge_width : rad, 10–90 % width of the target's edge; ``None`` for 1.5 θd.
    max_iterations, tolerance : the design stops when an iteration lowers the amplitude error by
        less than ``tolerance`` (relative), or after ``max_iterations``.
    max_error : an amplitude error still above it when the design stops improving is a stagnation.
    power : W.
    offset, tilt : beam pointing as in :class:`GaussianBeam`.

    Attributes
    ----------
    phase : (n, n) rad, the plate.
    target, far_field : (n, n) W/sr, radiant intensity asked for and achieved, on the angles
        ``angles`` (rad).
    history : amplitude error per iteration.
    stop : ``"converged"``, ``"stagnated"`` or ``"max_iterations"``.
    monotone : the error never rose.
    efficiency : power fraction inside the nominal disc.
    uniformity_rms, uniformity_pv : std/mean and (max−min)/mean of the far field where the target
        is at least 90 % of its plateau.
    edge_width : achieved 10–90 % width (rad).

    The beam is immutable and its arrays read-only.
    """

    def __init__(
        self,
        wavelength: float,
        waist_radius: float,
        angular_diameter: float,
        *,
        grid: int = 512,
        samples_per_waist: float = 8.0,
        edge_width: float | None = None,
        max_iterations: int = 300,
        tolerance: float = 1e-4,
        max_error: float = 0.05,
        power: float = 1.0,
        offset: Pair = (0.0, 0.0),
        tilt: Pair = (0.0, 0.0),
    ) -> None:
        power = _checks.real("power", power)
        if not power >= MIN_BEAM_POWER:  # the core refuses <= 0 and > 1e30 W
            raise ValueError(
                f"power = {power!r} is invalid: expected a power of at least {MIN_BEAM_POWER:g} W"
            )
        d = _core.design_flat_top(
            _checks.real("wavelength", wavelength),
            _checks.real("waist_radius", waist_radius),
            _checks.real("angular_diameter", angular_diameter),
            _checks.count("grid", grid, 1),
            _checks.real("samples_per_waist", samples_per_waist),
            0.0 if edge_width is None else _checks.positive("edge_width", edge_width),
            _checks.count("max_iterations", max_iterations, 1),
            _checks.real("tolerance", tolerance),
            _checks.real("max_error", max_error),
            power,
        )
        super().__init__(Field._from_core(d.field, d.spacing, wavelength), offset, tilt)
        self.waist_radius = float(waist_radius)
        self.angular_diameter = float(angular_diameter)
        self.phase: np.ndarray = d.phase
        self.target: np.ndarray = d.target
        self.far_field: np.ndarray = d.far_field
        self.angular_spacing: float = d.angular_spacing
        self.edge_width_target: float = d.edge_width_target
        self.history: np.ndarray = d.history
        self.stop: str = d.stop
        self.monotone: bool = d.monotone
        self.efficiency: float = d.efficiency
        self.uniformity_rms: float = d.uniformity_rms
        self.uniformity_pv: float = d.uniformity_pv
        self.edge_width: float = d.edge_width
        for array in (self.phase, self.target, self.far_field, self.history):
            array.flags.writeable = False
        object.__setattr__(self, "_sealed", True)

    def __setattr__(self, name: str, value) -> None:
        if self.__dict__.get("_sealed"):
            raise FrozenInstanceError(
                f"cannot assign to field {name!r}: a FlatTopBeam is immutable; with_pointing() "
                "gives a re-pointed copy, a new design needs a new FlatTopBeam"
            )
        super().__setattr__(name, value)

    def __delattr__(self, name: str) -> None:
        raise FrozenInstanceError(f"cannot delete field {name!r}: a FlatTopBeam is immutable")

    def __reduce__(self):
        # The design is kept, not redone: its results travel as they are, the field beam is checked
        # again.
        state = {k: v for k, v in self.__dict__.items() if k not in ("_native", "_sealed")}
        return _restore, (type(self), state)

    @property
    def iterations(self) -> int:
        return int(self.history.size)

    @property
    def angles(self) -> np.ndarray:
        """Far-field angles (rad) of the rows and columns of ``target`` and ``far_field``."""
        n = self.far_field.shape[0]
        return (np.arange(n) - n // 2) * self.angular_spacing

    def __repr__(self) -> str:
        return (
            f"FlatTopBeam(wavelength={self.wavelength:.4g} m, waist_radius={self.waist_radius:.4g} "
            f"m, angular_diameter={self.angular_diameter:.4g} rad: {self.stop} after "
            f"{self.iterations} iterations, efficiency {self.efficiency:.3f}, plateau rms "
            f"{self.uniformity_rms:.3g})"
        )


def _restore(cls, state: dict) -> FlatTopBeam:
    """An unpickled FlatTopBeam: the field beam built again from its field and pointing, the
    design's results set."""
    beam = cls.__new__(cls)
    FieldBeam.__init__(beam, state.pop("field"), state.pop("offset"), state.pop("tilt"))
    for name, value in state.items():
        if isinstance(
            value, np.ndarray
        ):  # unpickled: a new array; copied (copy.copy): the same read-only one
            value.flags.writeable = False
        object.__setattr__(beam, name, value)
    object.__setattr__(beam, "_sealed", True)
    return beam
