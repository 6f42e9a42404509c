"""A virtual bearing test machine: a bearing driven through an imposed displacement history.

Each sample of the history is one trial of the element followed by a commit, exactly as a
displacement-controlled test rig imposes it. The result is a tidy record of the histories
(time, displacement, velocity, force, mu, temperature, heat flux, axial load) with the
per-cycle force-deflection characteristics one call away.
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from dcfpb.common.validation import check_array
from isolator.bearing import DCFPBearing

HISTORY_FIELDS = (
    "time", "displacement", "velocity", "force", "friction_force", "mu", "temperature",
    "heat_flux", "axial_load",
)
UNITS = {
    "time": "s", "displacement": "m", "velocity": "m/s", "force": "N", "friction_force": "N",
    "mu": "-", "temperature": "degC", "heat_flux": "W/m^2", "axial_load": "N",
}


@dataclass(frozen=True)
class BearingTestResult:
    """Histories of a virtual bearing test, one value per sample of the imposed history.

    Attributes
    ----------
    time, displacement, velocity, force, friction_force, mu, temperature, heat_flux, axial_load
        Arrays in SI units (see ``UNITS``).
    bearing : DCFPBearing
        The bearing tested.
    name : str
        Name of the imposed history.
    wall_time : float
        Seconds the run took (for information; benchmarks measure speed properly).
    """

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    force: np.ndarray
    friction_force: np.ndarray
    mu: np.ndarray
    temperature: np.ndarray
    heat_flux: np.ndarray
    axial_load: np.ndarray
    bearing: DCFPBearing = field(repr=False)
    name: str = "imposed history"
    wall_time: float = 0.0

    def characteristics(self, **kwargs):
        """Per-cycle force-deflection characteristics (see :mod:`isolator.characteristics`)."""
        from isolator.characteristics import cycle_characteristics

        return cycle_characteristics(self.displacement, self.force, **kwargs)

    def to_csv(self, path: str | Path) -> Path:
        """Write time [s], displacement [m], velocity [m/s], force [N], mu [-] and
        temperature [degC] to a CSV file with one header line of those names."""
        path = Path(path)
        names = ("time", "displacement", "velocity", "force", "mu", "temperature")
        header = ",".join(names)
        data = np.column_stack([getattr(self, n) for n in names])
        np.savetxt(path, data, delimiter=",", header=header, comments="", fmt="%.10g")
        return path

    def to_dataset(self):
        """The histories as an ``xarray.Dataset`` indexed by time, with units attributes."""
        import xarray as xr

        data = {
            n: ("time", getattr(self, n), {"units": UNITS[n]})
            for n in HISTORY_FIELDS if n != "time"
        }
        return xr.Dataset(data, coords={"time": ("time", self.time, {"units": "s"})},
                          attrs={"history": self.name})


def imposed_history(
    time: np.ndarray, displacement: np.ndarray, velocity: np.ndarray | None, owner: str
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Check an imposed history and return it as float arrays ``(t [s], u [m], v [m/s])``.

    Times must be strictly increasing and the arrays of one length; without a velocity, the
    central-difference derivative of the displacement (``numpy.gradient``) is used. Errors
    name ``owner``.
    """
    t = check_array(time, "time", owner, min_length=2)
    u = check_array(displacement, "displacement", owner, min_length=2)
    if u.shape != t.shape:
        raise ValueError(f"The 'displacement' parameter of {owner} must have the length of "
                         f"'time' ({t.size}). Got {u.size} instead.")
    if np.any(np.diff(t) <= 0.0):
        raise ValueError(f"The 'time' parameter of {owner} must be strictly increasing.")
    if velocity is None:
        return t, u, np.gradient(u, t)
    v = check_array(velocity, "velocity", owner, min_length=2)
    if v.shape != t.shape:
        raise ValueError(f"The 'velocity' parameter of {owner} must have the length of "
                         f"'time' ({t.size}). Got {v.size} instead.")
    return t, u, v


def run_test(
    bearing: DCFPBearing,
    time: np.ndarray,
    displacement: np.ndarray,
    velocity: np.ndarray | None = None,
    *,
    name: str = "imposed history",
) -> BearingTestResult:
    """Drive ``bearing`` through an imposed relative displacement history.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing to test; a fresh element (at rest, unheated) is made for the run.
    time : array_like
        Strictly increasing sample times [s].
    displacement : array_like
        Imposed relative displacement of the plates [m].
    velocity : array_like, optional
        Imposed relative velocity [m/s]; by default the central-difference derivative of the
        displacement (``numpy.gradient``). Give the analytic velocity where it is known.
    name : str
        Name of the history, kept in the result.

    Returns
    -------
    BearingTestResult
    """
    owner = "run_test"
    t, u, v = imposed_history(time, displacement, velocity, owner)
    capacity = bearing.displacement_capacity
    if np.max(np.abs(u)) > capacity:
        raise ValueError(
            f"The 'displacement' parameter of {owner} must stay within the bearing's "
            f"displacement_capacity +-{capacity:g} m. Got a peak of {np.max(np.abs(u)):g} m "
            "instead."
        )
    start = _time.perf_counter()
    element = bearing.element()
    out = {n: np.empty(t.size) for n in HISTORY_FIELDS}
    shift = t[0]
    for i in range(t.size):
        # sample 0 is a trial at zero elapsed time: it sets mu and z but adds no heat
        element.set_trial(u[i], v[i], t[i] - shift)
        element.commit()
        s = element.committed
        out["force"][i] = s.force
        out["friction_force"][i] = s.friction_force
        out["mu"][i] = s.mu
        out["temperature"][i] = s.temperature
        out["heat_flux"][i] = s.heat_flux
        out["axial_load"][i] = s.axial_load
    out["time"], out["displacement"], out["velocity"] = t, u, v
    wall = _time.perf_counter() - start
    return BearingTestResult(**out, bearing=bearing, name=name, wall_time=wall)
