"""The virtual bearing test machine in 2D: a bearing driven through an imposed orbit.

Each sample of the orbit is one trial of the bidirectional element
(:class:`~isolator.bidirectional.element.BidirectionalElement`) followed by a commit, as the planar
rig
(:func:`isolator.testrig.run_test`) does along one axis. The result holds the force (n, 2), mu,
temperature and heat-flux histories, the per-cycle characteristics along each axis
(:func:`isolator.characteristics.cycle_characteristics` on each component) and the energies:
the work of the force, of its friction part and the heat put into the plates.
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.validation import check_array
from isolator.bearing import DCFPBearing
from isolator.bidirectional.element import BidirectionalElement
from isolator.bidirectional.orbits import Orbit
from isolator.friction import PTVFriction

AXES = ("x", "y")


def path_integral(displacement: np.ndarray, force: np.ndarray) -> float:
    """Integral of F . du along a 2D path by the trapezoid rule [J].

    Parameters
    ----------
    displacement, force : ndarray, shape (n, 2)
        Displacement [m] and force [N] at the samples.
    """
    du = np.diff(displacement, axis=0)
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * du))


@dataclass(frozen=True)
class OrbitTestResult:
    """Histories of a 2D virtual bearing test, one row per sample of the orbit.

    Attributes
    ----------
    time : ndarray, shape (n,)
        Sample times [s].
    displacement, velocity : ndarray, shape (n, 2)
        Imposed relative displacement [m] and velocity [m/s].
    force, friction_force : ndarray, shape (n, 2)
        Horizontal force and its friction part mu N z [N].
    z : ndarray, shape (n, 2)
        Hysteretic variable [-].
    mu, temperature, heat_flux, axial_load : ndarray, shape (n,)
        Friction coefficient [-], contact temperature [degC], heat flux into each sliding
        surface over the step ending at the sample [W/m^2], axial load [N].
    bearing : DCFPBearing
        The bearing tested.
    name : str
        Name of the orbit.
    stored_points : int
        Monitor points holding a history at the end, per plate (precise model; 0 otherwise).
    wall_time : float
        Seconds the run took (for information).
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
    name: str = "orbit"
    stored_points: int = 0
    wall_time: float = 0.0

    def characteristics(self, axis: int | str, **kwargs):
        """Per-cycle characteristics of the loop along ``axis`` (0/``"x"`` or 1/``"y"``): see
        :func:`isolator.characteristics.cycle_characteristics` (same keyword arguments)."""
        from isolator.characteristics import cycle_characteristics

        index = AXES.index(axis) if isinstance(axis, str) else int(axis)
        if index not in (0, 1):
            raise ValueError(f"The 'axis' parameter of OrbitTestResult.characteristics must be "
                             f"0, 1, 'x' or 'y'. Got {axis!r} instead.")
        return cycle_characteristics(self.displacement[:, index], self.force[:, index],
                                     self.time, **kwargs)

    def dissipated_energy(self, samples: slice = slice(None)) -> float:
        """Work of the force along the orbit, integral of F . du [J] (trapezoid), over the
        ``samples`` (e.g. one block of :meth:`isolator.bidirectional.orbits.Orbit.segment_slices`).
        Over a
        closed path the restoring part cancels and this is the energy dissipated."""
        return path_integral(self.displacement[samples], self.force[samples])

    def friction_work(self, samples: slice = slice(None)) -> float:
        """Work of the friction force alone, integral of mu N z . du [J]."""
        return path_integral(self.displacement[samples], self.friction_force[samples])

    def to_csv(self, path: str | Path) -> Path:
        """Write time [s], displacement and velocity (x, y) [m, m/s], force (x, y) [N], mu [-]
        and temperature [degC] to a CSV file with one header line of their names."""
        path = Path(path)
        columns = {"time": self.time}
        for name in ("displacement", "velocity", "force"):
            for i, axis in enumerate(AXES):
                columns[f"{name}_{axis}"] = getattr(self, name)[:, i]
        columns |= {"mu": self.mu, "temperature": self.temperature}
        np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
                   header=",".join(columns), comments="", fmt="%.10g")
        return path

    def heat_input(self, samples: slice = slice(None)) -> float:
        """Heat put into the plates [J]: over each step, the flux of Eq. 5 on every sliding
        surface times the contact area, sum of surfaces q_n pi r^2 (t_n - t_(n-1)); for the
        models without heating, the friction power mu N |v| integrated the same way."""
        t = self.time[samples]
        friction = self.bearing.friction
        if isinstance(friction, PTVFriction):
            area = self.bearing.contact_area
            power = friction.surfaces * self.heat_flux[samples][1:] * area
        else:
            speed = np.hypot(*self.velocity[samples][1:].T)
            power = self.mu[samples][1:] * self.axial_load[samples][1:] * speed
        return float(np.sum(power * np.diff(t)))


def run_orbit_test(
    bearing: DCFPBearing,
    time: ArrayLike,
    displacement: ArrayLike,
    velocity: ArrayLike | None = None,
    *,
    name: str = "orbit",
    grid_orientation: float | None = None,
) -> OrbitTestResult:
    """Drive ``bearing`` through an imposed 2D relative displacement history.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing to test; a fresh bidirectional element (at rest, unheated) is made.
    time : array_like, shape (n,)
        Strictly increasing sample times [s].
    displacement : array_like, shape (n, 2)
        Imposed relative displacement of the plates (x, y) [m], within the displacement
        capacity (a radius).
    velocity : array_like, shape (n, 2), optional
        Imposed relative velocity [m/s]; by default the central-difference derivative of the
        displacement (``numpy.gradient``).
    name : str
        Name of the orbit, kept in the result.
    grid_orientation : float or None
        Orientation of the precise model's monitor grid [deg]; None follows the motion.

    Returns
    -------
    OrbitTestResult
    """
    owner = "run_orbit_test"
    t = check_array(time, "time", owner, min_length=2)
    if np.any(np.diff(t) <= 0.0):
        raise ValueError(f"The 'time' parameter of {owner} must be strictly increasing.")
    u = check_array(displacement, "displacement", owner, ndim=2, min_length=2)
    if u.shape != (t.size, 2):
        raise ValueError(f"The 'displacement' parameter of {owner} must have the shape "
                         f"({t.size}, 2). Got {u.shape} instead.")
    if velocity is None:
        v = np.gradient(u, t, axis=0)
    else:
        v = check_array(velocity, "velocity", owner, ndim=2, min_length=2)
        if v.shape != u.shape:
            raise ValueError(f"The 'velocity' parameter of {owner} must have the shape "
                             f"{u.shape}. Got {v.shape} instead.")
    capacity = bearing.displacement_capacity
    peak = float(np.max(np.hypot(u[:, 0], u[:, 1])))
    if peak > capacity:
        raise ValueError(f"The 'displacement' parameter of {owner} must stay within the "
                         f"bearing's displacement_capacity {capacity:g} m (a radius). Got a "
                         f"peak of {peak:g} m instead.")
    start = _time.perf_counter()
    element = BidirectionalElement(bearing, grid_orientation)
    out = {name_: np.empty((t.size, 2)) for name_ in ("force", "friction_force", "z")}
    out |= {name_: np.empty(t.size) for name_ in ("mu", "temperature", "heat_flux",
                                                  "axial_load")}
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
    return OrbitTestResult(t, u, v, **out, bearing=bearing, name=name, stored_points=stored,
                           wall_time=_time.perf_counter() - start)


def run_orbit(bearing: DCFPBearing, orbit: Orbit, *,
              grid_orientation: float | None = None) -> OrbitTestResult:
    """:func:`run_orbit_test` on an :class:`~isolator.bidirectional.orbits.Orbit` (its exact
    velocity)."""
    return run_orbit_test(bearing, orbit.time, orbit.displacement, orbit.velocity,
                          name=orbit.name, grid_orientation=grid_orientation)
