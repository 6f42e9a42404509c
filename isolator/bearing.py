"""The double concave friction pendulum bearing (DCFPB) element, in one or two directions.

Horizontal force [N] for a relative displacement u [m] and velocity v [m/s] of the two plates
(floats along x in one direction, (x, y) vectors in two):

    F = N u / R_eff + mu(p, |v|, T) N z,

N the axial load [N], R_eff the effective radius [m], p = N / (pi r^2) the contact pressure [Pa],
z the hysteretic variable of an isotropic return map (:func:`isotropic_return_map`), so the
friction force has magnitude mu N and the direction of sliding. The restoring law is
``"linear"``, N u / R_eff (the paper's), or ``"spherical"``, N u / sqrt(R_eff^2 - |u|^2)
(OpenSees FPBearingPTV's). mu, temperature and heat flux come from the friction model
(:class:`isolator.friction.FrictionModel`) at every trial.

:class:`DCFPBearing` holds the frozen parameters, :class:`BearingElement` the state, with
set_trial / commit / revert as OpenSees elements. Along any fixed direction through the centre
the element in two directions gives the element in one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.errors import CapacityExceeded, InputError, InputTypeError
from dcfpb.common.validation import check_array, check_choice, check_instance, check_int, check_real
from isolator.friction import FrictionModel, FrictionState


@dataclass(frozen=True)
class AxialLoadHistory:
    """An axial load varying in time: the compressive ``load`` [N] (zero or negative: uplift) at
    strictly increasing ``time`` [s], linear in between and held constant outside."""

    time: np.ndarray
    load: np.ndarray

    def __post_init__(self) -> None:
        owner = type(self).__name__
        time = check_array(self.time, "time", owner, min_length=1, increasing=True)
        load = check_array(self.load, "load", owner, min_length=1, length_of=("time", time.size))
        object.__setattr__(self, "time", time)
        object.__setattr__(self, "load", load)

    def at(self, time: float) -> float:
        """Axial load at ``time`` [N]."""
        return float(np.interp(time, self.time, self.load))


class BearingTrial(NamedTuple):
    """Force F [N] and consistent tangents of a trial, ``stiffness`` d F / d u [N/m] and
    ``damping`` d F / d v [N s/m] (from the velocity dependence of mu): floats in one direction,
    a (2,) vector and (2, 2) matrices in two."""

    force: float | np.ndarray
    stiffness: float | np.ndarray
    damping: float | np.ndarray


class BearingState(NamedTuple):
    """A trial or committed state of the element: displacement [m], velocity [m/s], force and
    friction_force [N] and z [-], floats in one direction and (x, y) arrays of shape (2,) in two;
    time [s], mu [-], temperature [degC], heat_flux [W/m^2] and axial_load [N], floats."""

    time: float
    displacement: float | np.ndarray
    velocity: float | np.ndarray
    force: float | np.ndarray
    friction_force: float | np.ndarray
    z: float | np.ndarray
    mu: float
    temperature: float
    heat_flux: float
    axial_load: float


def isotropic_return_map(zx: float, zy: float, dux: float, duy: float,
                         yield_displacement: float) -> tuple[float, ...]:
    """The trial hysteretic variable z (x, y) [-], |z| <= 1, after a displacement increment
    (``dux``, ``duy``) [m] from the committed (``zx``, ``zy``) for a yield displacement u_y [m],
    and d z / d u row by row (xx, xy, yx, yy) [1/m]: z* = z_c + du / u_y kept when |z*| < 1, else
    the radial return z* / |z*|."""
    px = zx + dux / yield_displacement
    py = zy + duy / yield_displacement
    size = abs(px) if py == 0.0 else math.hypot(px, py)
    if size >= 1.0:
        zx, zy = px / size, py / size
        scale = yield_displacement * size
        return (zx, zy, (1.0 - zx * zx) / scale, -zx * zy / scale, -zy * zx / scale,
                (1.0 - zy * zy) / scale)
    elastic = 1.0 / yield_displacement
    return px, py, elastic, 0.0, 0.0, elastic


def slider_contact_area(slider_diameter: float) -> float:
    """Contact area pi r^2 [m^2] of a slider of ``slider_diameter`` [m], r = half of it."""
    return math.pi * (0.5 * slider_diameter) ** 2


class SliderContact:
    """The contact of the slider of a class with a ``slider_diameter`` [m]: a bearing
    (:class:`DCFPBearing`) or the bearing of a test campaign
    (:class:`isolator.diagnosis.data.Campaign`)."""

    @property
    def contact_radius(self) -> float:
        """Contact radius r = half the slider diameter [m]."""
        return 0.5 * self.slider_diameter

    @property
    def contact_area(self) -> float:
        """Contact area pi r^2 [m^2]."""
        return slider_contact_area(self.slider_diameter)


@dataclass(frozen=True)
class DCFPBearing(SliderContact):
    """Parameters of a double concave friction pendulum bearing.

    Parameters
    ----------
    effective_radius : float
        Effective radius R_eff [m]; ``inf`` for a flat slider (no restoring stiffness).
    slider_diameter : float
        Slider diameter [m]; the contact radius is half of it.
    axial_load : float or AxialLoadHistory or None
        Compressive axial load N [N], constant or in time (a bearing test needs one); None for a
        bearing in a building, which loads it with its share of the weight.
    friction : FrictionModel
        Friction model of the sliding surfaces (required): a ``ConstantFriction``, a
        ``PTVFriction`` or any object with their ``bind``, ``name`` and ``initial_temperature``.
    yield_displacement : float
        Yield displacement u_y of the return map [m].
    displacement_capacity : float
        Largest relative displacement of the plates [m] (a radius in two directions); it sizes
        the precise model's monitor points.
    restoring : {"linear", "spherical"}
        Restoring force law (see the module docstring).
    """

    effective_radius: float
    slider_diameter: float
    axial_load: float | AxialLoadHistory | None = None
    friction: FrictionModel | None = None
    yield_displacement: float = 5.0e-4
    displacement_capacity: float = 0.6
    restoring: str = "linear"

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.effective_radius, "effective_radius", owner, low=0.0, low_open=True,
                   allow_inf=True)
        check_real(self.slider_diameter, "slider_diameter", owner, low=0.0, low_open=True,
                   high=10.0)
        if self.axial_load is not None and not isinstance(self.axial_load, AxialLoadHistory):
            check_real(self.axial_load, "axial_load", owner, low=0.0, low_open=True)
        if not all(hasattr(self.friction, name) for name in ("bind", "name",
                                                             "initial_temperature")):
            raise InputTypeError(
                f"The 'friction' parameter of {owner} must be a friction model (a "
                "ConstantFriction, a PTVFriction or another FrictionModel with bind, name and "
                f"initial_temperature). Got {self.friction!r} instead."
            )
        check_real(self.yield_displacement, "yield_displacement", owner, low=0.0,
                   low_open=True, high=0.1)
        check_real(self.displacement_capacity, "displacement_capacity", owner, low=0.0,
                   low_open=True, high=10.0)
        check_choice(self.restoring, "restoring", owner, ("linear", "spherical"))
        if self.restoring == "spherical" and not (
            self.displacement_capacity < self.effective_radius
        ):
            raise InputError(
                f"The 'displacement_capacity' parameter of {owner} must be below the "
                f"effective radius {self.effective_radius:g} m for the spherical law. "
                f"Got {self.displacement_capacity!r} instead."
            )

    def axial_load_at(self, time: float) -> float:
        """Axial load N at ``time`` [N]."""
        if self.axial_load is None:
            raise InputError(
                f"This {type(self).__name__} has no axial load: give 'axial_load' [N] (a "
                "positive float or an AxialLoadHistory), or place it in a building, whose "
                "weight shared by its bearings is the load.")
        if isinstance(self.axial_load, AxialLoadHistory):
            return self.axial_load.at(time)
        return float(self.axial_load)

    @property
    def pendulum_stiffness(self) -> float:
        """Post-yield stiffness N / R_eff at the initial axial load [N/m]."""
        return self.axial_load_at(0.0) / self.effective_radius

    def element(self, dimension: int = 1,
                grid_orientation: float | None = None) -> BearingElement:
        """A new element at rest (u = 0, z = 0, t = 0) with unheated plates, moving in
        ``dimension`` 1 (along x) or 2 directions; see :class:`BearingElement`."""
        return BearingElement(self, dimension, grid_orientation)


def beyond_capacity_message(displacement: float, time: float, capacity: float, *,
                            trial: bool = False, detail: str = "") -> str:
    """The message of a run ended by a bearing beyond its displacement capacity: the isolator
    ``displacement`` [m] at ``time`` [s] past the ``capacity`` [m], in an uncommitted ``trial``
    or a committed step, with what the model said (``detail``, e.g. the monitor line)."""
    where = " in a trial of the step" if trial else ""
    detail = f" ({detail[:1].lower()}{detail[1:].rstrip('.')})" if detail else ""
    return (f"Capacity exceeded: the isolator displacement reached {abs(displacement):.4g} m "
            f"at t = {time:.6g} s{where}, beyond the bearing's displacement_capacity "
            f"{capacity:g} m{detail}: the bearing would hit its restrainer, so the response "
            "from then on is not physical.")


def trial_failure(bearing: DCFPBearing, displacement: float, time: float,
                  detail: str) -> CapacityExceeded:
    """The error of a trial displacement [m] at ``time`` [s] the model cannot evaluate (``detail``
    says why): a capacity failure beyond the displacement capacity, else a ``"model"`` failure."""
    capacity = bearing.displacement_capacity
    if abs(displacement) > capacity:
        return CapacityExceeded(beyond_capacity_message(displacement, time, capacity,
                                                        trial=True, detail=detail))
    return CapacityExceeded(
        f"At t = {time:.6g} s a trial isolator displacement of {abs(displacement):.4g} m, "
        f"within the displacement_capacity {capacity:g} m, is outside the bearing model's "
        f"range: {detail}", kind="model")


def _pair(value: ArrayLike, name: str) -> tuple[float, float]:
    array = np.asarray(value, dtype=float)
    if array.shape != (2,) or not np.all(np.isfinite(array)):
        raise InputError(f"The {name!r} parameter of BearingElement.set_trial must be a finite "
                         f"(x, y) pair for a bearing in two directions. Got {value!r} instead.")
    return float(array[0]), float(array[1])


class BearingElement:
    """The DCFPB element in one or two directions, with set_trial / commit / revert; a trial is
    a pure function of the committed state and its arguments.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing's parameters.
    dimension : {1, 2}
        1: displacement, velocity and force are floats along x; 2: (x, y) vectors.
    grid_orientation : float or None
        Orientation of the precise model's monitor grid in two directions [deg]; None follows the
        motion (:class:`~isolator.monitor_grid.MonitorGrid`).
    """

    def __init__(self, bearing: DCFPBearing, dimension: int = 1,
                 grid_orientation: float | None = None) -> None:
        self.bearing = check_instance(bearing, "bearing", "BearingElement", DCFPBearing,
                                      "a DCFPBearing")
        self.dimension = check_int(dimension, "dimension", "BearingElement", low=1, high=2)
        self._friction: FrictionState = bearing.friction.bind(
            bearing.contact_radius, bearing.displacement_capacity, self.dimension,
            grid_orientation)
        self._radius = bearing.effective_radius
        self._spherical = bearing.restoring == "spherical"
        self._yield = bearing.yield_displacement
        self._area = bearing.contact_area
        self._constant_load = (None if isinstance(bearing.axial_load, AxialLoadHistory)
                               else bearing.axial_load)
        n0 = bearing.axial_load_at(0.0)
        # at rest: mu at zero speed (a trial of zero length adds no heat)
        zero = (0.0, 0.0)
        mu0 = (self._friction.trial(zero, zero, n0 / bearing.contact_area, 0.0).mu
               if n0 > 0 else 0.0)
        self._friction.revert()
        self._floats = (0.0, 0.0, 0.0, 0.0, 0.0)  # committed time, u (x, y), z (x, y)
        self._trial_floats = self._floats
        self._committed = self._state(0.0, zero, zero, zero, zero, zero, mu0,
                                      bearing.friction.initial_temperature, 0.0, n0)
        self._trial = self._committed

    @property
    def committed(self) -> BearingState:
        """The last committed state."""
        return self._committed

    @property
    def trial_state(self) -> BearingState:
        """The state of the last trial (equals the committed state after commit/revert)."""
        return self._trial

    @property
    def friction_state(self) -> FrictionState:
        """The bound friction evaluator (its ``temperature_field`` reads the plates)."""
        return self._friction

    def _state(self, time: float, u: tuple, v: tuple, force: tuple, friction_force: tuple,
               z: tuple, mu: float, temperature: float, heat_flux: float,
               load: float) -> BearingState:
        if self.dimension == 1:
            return BearingState(time, u[0], v[0], force[0], friction_force[0], z[0], mu,
                                temperature, heat_flux, load)
        return BearingState(time, np.array(u), np.array(v), np.array(force),
                            np.array(friction_force), np.array(z), mu, temperature, heat_flux,
                            load)

    def _restoring(self, ux: float, uy: float, n: float,
                   time: float) -> tuple[float, float, float, float, float]:
        """Restoring force (x, y) [N] and its stiffness (xx, xy, yy) [N/m]."""
        if math.isinf(self._radius):
            return 0.0, 0.0, 0.0, 0.0, 0.0
        if self._spherical:
            squared = self._radius**2 - (ux * ux + uy * uy)
            if not squared > 0.0:
                raise trial_failure(self.bearing, math.hypot(ux, uy), time, f"at the effective "
                                    f"radius {self._radius!r} m of the spherical law")
            root = math.sqrt(squared)
            cube = root**3
            return (n * ux / root, n * uy / root, n * (1.0 / root + ux * ux / cube),
                    n * ux * uy / cube, n * (1.0 / root + uy * uy / cube))
        return n * ux / self._radius, n * uy / self._radius, n / self._radius, 0.0, \
            n / self._radius

    def set_trial(self, displacement: float | ArrayLike, velocity: float | ArrayLike,
                  time: float, axial_load: float | None = None) -> BearingTrial:
        """Force [N] and tangents d F / d u [N/m], d F / d v [N s/m] (at fixed load) at a trial
        displacement [m], velocity [m/s] and time [s]: floats in one direction, (x, y) pairs in
        two. ``axial_load`` [N], when given, replaces the bearing's own for this trial; zero or
        negative is uplift: no contact, force or heat, and the plates cool.

        Raises
        ------
        ValueError
            If ``time`` is before the last committed time, or a vector is not a finite pair.
        dcfpb.common.errors.CapacityExceeded
            If the model cannot evaluate the displacement (:func:`trial_failure`).
        """
        if self.dimension == 1:
            ux, uy, vx, vy = float(displacement), 0.0, float(velocity), 0.0
        else:
            (ux, uy), (vx, vy) = _pair(displacement, "displacement"), _pair(velocity, "velocity")
        committed_time, cux, cuy, czx, czy = self._floats
        dt = time - committed_time
        if dt < 0.0:
            raise InputError(
                f"The trial time {time!r} s of BearingElement.set_trial is before the last "
                f"committed time {committed_time!r} s."
            )
        if axial_load is not None:
            n = float(axial_load)
        else:
            n = self._constant_load
            if n is None:
                n = self.bearing.axial_load_at(time)
        zx, zy, dxx, dxy, dyx, dyy = isotropic_return_map(czx, czy, ux - cux, uy - cuy,
                                                           self._yield)
        try:
            if n <= 0.0:  # uplift: no contact, no force, no heat; the plates cool
                friction = self._friction.lifted((ux, uy), dt)
            else:
                friction = self._friction.trial((ux, uy), (vx, vy), n / self._area, dt)
        except CapacityExceeded as error:
            raise trial_failure(self.bearing, math.hypot(ux, uy), time, str(error)) from None
        if n <= 0.0:
            n = rx = ry = kxx = kxy = kyy = 0.0
        else:
            rx, ry, kxx, kxy, kyy = self._restoring(ux, uy, n, time)
        mu_n = friction.mu * n
        ffx, ffy = mu_n * zx, mu_n * zy
        fx, fy = rx + ffx, ry + ffy
        self._trial_floats = (time, ux, uy, zx, zy)
        if self.dimension == 1:
            self._trial = BearingState(time, ux, vx, fx, ffx, zx, friction.mu,
                                       friction.temperature, friction.heat_flux, n)
        else:
            self._trial = self._state(time, (ux, uy), (vx, vy), (fx, fy), (ffx, ffy),
                                      (zx, zy), friction.mu, friction.temperature,
                                      friction.heat_flux, n)
        speed = abs(vx) if vy == 0.0 else math.hypot(vx, vy)
        # d mu / d v = d mu / d|v| v / |v|; d mu / d|v| is negative on a hot plate at speed
        gx = gy = 0.0
        if speed > 0.0:
            gx, gy = friction.dmu_dspeed * (vx / speed), friction.dmu_dspeed * (vy / speed)
        nzx, nzy = n * zx, n * zy
        if self.dimension == 1:
            return BearingTrial(fx, kxx + mu_n * dxx, nzx * gx)
        return BearingTrial(
            np.array([fx, fy]),
            np.array([[kxx + mu_n * dxx, kxy + mu_n * dxy], [kxy + mu_n * dyx, kyy + mu_n * dyy]]),
            np.array([[nzx * gx, nzx * gy], [nzy * gx, nzy * gy]]))

    def commit(self) -> None:
        """Accept the last trial: its state becomes the committed state, its heat is added."""
        self._friction.commit()
        self._committed = self._trial
        self._floats = self._trial_floats

    def revert(self) -> None:
        """Drop the last trial and return to the committed state exactly."""
        self._friction.revert()
        self._trial = self._committed
        self._trial_floats = self._floats
