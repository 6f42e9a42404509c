"""A virtual bearing test machine: a bearing driven through an imposed displacement history,
one trial and commit per sample, in one direction (shape (n,)) or in two (an orbit, shape
(n, 2)); the result holds the histories, their per-cycle characteristics and energies.
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_array, check_instance
from isolator.bearing import DCFPBearing
from isolator.characteristics import magnitude, path_integral
from isolator.orbits import Orbit

AXES = ("x", "y")
HISTORY_FIELDS = (
    "time", "displacement", "velocity", "force", "friction_force", "z", "mu", "temperature",
    "heat_flux", "axial_load",
)
UNITS = {
    "time": "s", "displacement": "m", "velocity": "m/s", "force": "N", "friction_force": "N",
    "z": "-", "mu": "-", "temperature": "degC", "heat_flux": "W/m^2", "axial_load": "N",
}
_VECTORS = ("displacement", "velocity", "force", "friction_force", "z")


@dataclass(frozen=True)
class BearingTestResult:
    """Histories of a virtual bearing test, one value (or (x, y) row) per sample.

    Attributes
    ----------
    time : ndarray, shape (n,)
        Sample times [s].
    displacement, velocity, force, friction_force, z : ndarray, shape (n,) or (n, 2)
        Imposed relative displacement [m] and velocity [m/s], horizontal force and its friction
        part mu N z [N], hysteretic variable [-]: in one direction, or (x, y) in two.
    mu, temperature, heat_flux, axial_load : ndarray, shape (n,)
        Friction coefficient [-], contact temperature [degC], heat flux into each sliding
        surface over the step ending at the sample [W/m^2], axial load [N].
    bearing, name : DCFPBearing, str
        The bearing tested and the name of the imposed history.
    stored_points : int
        Monitor points per plate holding a history at the end (the precise model in two
        directions; 0 otherwise).
    wall_time : float
        Time the run took [s].
    """

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    force: np.ndarray
    friction_force: np.ndarray
    z: np.ndarray
    mu: np.ndarray
    temperature: np.ndarray
    heat_flux: np.ndarray
    axial_load: np.ndarray
    bearing: DCFPBearing = field(repr=False)
    name: str = "imposed history"
    stored_points: int = 0
    wall_time: float = 0.0

    @property
    def dimension(self) -> int:
        """1 for a test in one direction, 2 for an orbit."""
        return 1 if self.displacement.ndim == 1 else 2

    def _axis(self, values: np.ndarray, axis: int | str) -> np.ndarray:
        index = AXES.index(axis) if isinstance(axis, str) and axis in AXES else axis
        if index not in range(self.dimension):
            allowed = "0 or 'x'" if self.dimension == 1 else "0, 1, 'x' or 'y'"
            raise InputError(f"The 'axis' parameter of BearingTestResult must be {allowed}. "
                             f"Got {axis!r} instead.")
        return values if self.dimension == 1 else values[:, index]

    def characteristics(self, axis: int | str = 0, **kwargs):
        """Per-cycle characteristics of the loop along ``axis`` (0/``"x"`` or 1/``"y"``): see
        :func:`isolator.characteristics.cycle_characteristics` (same keyword arguments)."""
        from isolator.characteristics import cycle_characteristics

        return cycle_characteristics(self._axis(self.displacement, axis),
                                     self._axis(self.force, axis), self.time, **kwargs)

    def dissipated_energy(self, samples: slice = slice(None)) -> float:
        """Work of the force along the path, integral of F . du [J] (trapezoid), over the
        ``samples`` (e.g. one block of :meth:`isolator.orbits.Orbit.segment_slices`). Over a
        closed path the restoring part cancels and this is the energy dissipated."""
        return path_integral(self.displacement[samples], self.force[samples])

    def friction_work(self, samples: slice = slice(None)) -> float:
        """Work of the friction force alone, integral of mu N z . du [J]."""
        return path_integral(self.displacement[samples], self.friction_force[samples])

    def heat_input(self, samples: slice = slice(None)) -> float:
        """Heat put into the plates [J]: over each step, the flux of Eq. 5 on every sliding
        surface times the contact area; for the models without heating, the friction power
        mu N |v| integrated the same way."""
        t = self.time[samples]
        surfaces = getattr(self.bearing.friction, "surfaces", None)
        if getattr(self.bearing.friction, "heats", False):
            power = surfaces * self.heat_flux[samples][1:] * self.bearing.contact_area
        else:
            velocity = self.velocity[samples][1:]
            power = self.mu[samples][1:] * self.axial_load[samples][1:] * magnitude(velocity)
        return float(np.sum(power * np.diff(t)))

    def columns(self) -> dict[str, np.ndarray]:
        """The histories written by :meth:`to_csv`: time [s], displacement [m], velocity [m/s],
        force [N] (one column each in one direction; ``_x`` and ``_y`` in two), mu [-] and
        temperature [degC]."""
        columns = {"time": self.time}
        for name in ("displacement", "velocity", "force"):
            values = getattr(self, name)
            if self.dimension == 1:
                columns[name] = values
            else:
                columns |= {f"{name}_{axis}": values[:, i] for i, axis in enumerate(AXES)}
        return columns | {"mu": self.mu, "temperature": self.temperature}

    def to_csv(self, path: str | Path) -> Path:
        """Write :meth:`columns` to a CSV file with one header line of their names."""
        path = Path(path)
        columns = self.columns()
        np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
                   header=",".join(columns), comments="", fmt="%.10g")
        return path

    def to_dataset(self):
        """The histories as an ``xarray.Dataset`` indexed by time (and ``direction`` for an
        orbit), with units attributes."""
        import xarray as xr

        data = {}
        for name in HISTORY_FIELDS[1:]:
            dims = ("time", "direction") if name in _VECTORS and self.dimension == 2 else "time"
            data[name] = (dims, getattr(self, name), {"units": UNITS[name]})
        coords = {"time": ("time", self.time, {"units": "s"})}
        if self.dimension == 2:
            coords["direction"] = list(AXES)
        return xr.Dataset(data, coords=coords, attrs={"history": self.name})


def imposed_history(time: ArrayLike, displacement: ArrayLike, velocity: ArrayLike | None,
                    owner: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Check an imposed history and return it as float arrays ``(t [s], u [m], v [m/s])``:
    strictly increasing times, a displacement of shape (n,) or (n, 2), a velocity of the same
    shape or None (then ``numpy.gradient`` of the displacement). Errors name ``owner``."""
    t = check_array(time, "time", owner, min_length=2, increasing=True)
    ndim = 2 if np.ndim(displacement) == 2 else 1  # two directions or one
    u = check_array(displacement, "displacement", owner, ndim=ndim, min_length=2)
    shape = (t.size, 2) if ndim == 2 else t.shape
    if u.shape != shape:
        raise InputError(f"The 'displacement' parameter of {owner} must have the shape "
                         f"{shape} (one row per time). Got {u.shape} instead.")
    if velocity is None:
        return t, u, np.gradient(u, t, axis=0)
    v = check_array(velocity, "velocity", owner, ndim=u.ndim, min_length=2)
    if v.shape != u.shape:
        raise InputError(f"The 'velocity' parameter of {owner} must have the shape {u.shape} "
                         f"of 'displacement'. Got {v.shape} instead.")
    return t, u, v


def run_test(
    bearing: DCFPBearing,
    time: ArrayLike,
    displacement: ArrayLike,
    velocity: ArrayLike | None = None,
    *,
    name: str = "imposed history",
    grid_orientation: float | None = None,
) -> BearingTestResult:
    """Drive a fresh element of ``bearing`` (at rest, unheated) through an imposed relative
    displacement history.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing to test.
    time : array_like, shape (n,)
        Strictly increasing sample times [s].
    displacement : array_like, shape (n,) or (n, 2)
        Imposed relative displacement of the plates [m], in one direction or (x, y) in two,
        within the bearing's displacement capacity (a radius in two directions).
    velocity : array_like, optional
        Imposed relative velocity [m/s], the shape of ``displacement``; by default the
        central-difference derivative of the displacement.
    name : str
        Name of the history, kept in the result.
    grid_orientation : float or None
        Orientation of the precise model's monitor grid in two directions [deg]; None follows the
        motion.
    """
    owner = "run_test"
    check_instance(bearing, "bearing", owner, DCFPBearing, "a DCFPBearing")
    t, u, v = imposed_history(time, displacement, velocity, owner)
    reach = magnitude(u)
    capacity = bearing.displacement_capacity
    if np.max(reach) > capacity:
        raise InputError(
            f"The 'displacement' parameter of {owner} must stay within the bearing's "
            f"displacement_capacity {capacity:g} m{' (a radius)' if u.ndim == 2 else ''}. Got "
            f"a peak of {np.max(reach):g} m instead."
        )
    start = _time.perf_counter()
    element = bearing.element(u.ndim, grid_orientation)
    out = {n: np.empty(u.shape) for n in _VECTORS[2:]}
    out |= {n: np.empty(t.size) for n in ("mu", "temperature", "heat_flux", "axial_load")}
    shift = t[0]
    for i in range(t.size):
        # sample 0 is a trial at zero elapsed time: it sets mu and z but adds no heat
        element.set_trial(u[i], v[i], t[i] - shift)
        element.commit()
        s = element.committed
        out["force"][i], out["friction_force"][i], out["z"][i] = s.force, s.friction_force, s.z
        out["mu"][i], out["temperature"][i] = s.mu, s.temperature
        out["heat_flux"][i], out["axial_load"][i] = s.heat_flux, s.axial_load
    stored = getattr(getattr(element.friction_state, "heating", None), "stored_points", 0)
    return BearingTestResult(t, u, v, **out, bearing=bearing, name=name, stored_points=stored,
                             wall_time=_time.perf_counter() - start)


def run_orbit(bearing: DCFPBearing, orbit: Orbit, *,
              grid_orientation: float | None = None) -> BearingTestResult:
    """:func:`run_test` on an :class:`~isolator.orbits.Orbit` (its exact velocity)."""
    check_instance(bearing, "bearing", "run_orbit", DCFPBearing, "a DCFPBearing")
    check_instance(orbit, "orbit", "run_orbit", Orbit, "an Orbit (isolator.orbit)")
    return run_test(bearing, orbit.time, orbit.displacement, orbit.velocity, name=orbit.name,
                    grid_orientation=grid_orientation)
