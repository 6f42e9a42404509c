"""The bidirectional DCFPB element: displacement and force as vectors in the horizontal plane.

Horizontal force for a relative displacement u = (u_x, u_y) and velocity v of the plates:

    F = N u / R_eff + mu(p, |v|, T) N z,

with z a vector hysteretic variable of an isotropic elastic-plastic return map (|z| <= 1, on
the unit circle while sliding; :func:`isotropic_return_map`), so the friction force has the
magnitude mu N and the direction of the sliding. The restoring law is the planar element's
(``"linear"`` N u / R_eff or ``"spherical"`` N u / sqrt(R_eff^2 - |u|^2)), the slider sits at
u / 2 on each plate and mu, the temperature and the heat flux come from the 2D friction
evaluators (:mod:`isolator.bidirectional.friction`, the precise model on a monitor grid,
:mod:`isolator.bidirectional.heating`).

The element takes the parameters of the planar one (:class:`~isolator.bearing.DCFPBearing`;
``displacement_capacity`` is then a radius) and keeps its contract: ``set_trial(u, v, time)``
returns the force and the consistent 2x2 tangents d F / d u and d F / d v and is a pure
function of the committed state; ``commit()`` accepts it (only then is its heat added);
``revert()`` drops it. Along any fixed direction through the centre the element gives the
planar element's force, mu and temperature (``tests/verification/test_bidirectional.py``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from dcfpb.common.errors import CapacityExceeded
from isolator.bearing import DCFPBearing, trial_failure
from isolator.bidirectional.friction import bind_plate_friction
from isolator.friction import PTVFriction

_IDENTITY = np.eye(2)


def isotropic_return_map(z_committed: np.ndarray, increment: np.ndarray,
                         yield_displacement: float) -> tuple[np.ndarray, np.ndarray]:
    """The hysteretic variable after a displacement increment, and its tangent.

    The elastic predictor z* = z_c + du / u_y is returned when |z*| < 1, else its projection
    on the unit circle z* / |z*| (radial return of a von Mises-like law in 2D; in 1D it is the
    planar element's clip of z to +-1).

    Parameters
    ----------
    z_committed : ndarray, shape (2,)
        Committed hysteretic variable [-], |z| <= 1.
    increment : ndarray, shape (2,)
        Displacement increment since the commit [m].
    yield_displacement : float
        u_y [m].

    Returns
    -------
    z : ndarray, shape (2,)
        Trial hysteretic variable [-].
    dz_du : ndarray, shape (2, 2)
        Consistent tangent d z / d u [1/m]: I / u_y when elastic, (I - z z^T) / (u_y |z*|)
        when sliding.
    """
    predictor = z_committed + increment / yield_displacement
    size = math.hypot(predictor[0], predictor[1])
    if size >= 1.0:
        z = predictor / size
        return z, (_IDENTITY - np.outer(z, z)) / (yield_displacement * size)
    return predictor, _IDENTITY / yield_displacement


class PlanarTrial(NamedTuple):
    """Force and consistent tangents of a 2D trial state.

    Attributes
    ----------
    force : ndarray, shape (2,)
        Horizontal force F [N].
    stiffness : ndarray, shape (2, 2)
        d F / d u [N/m].
    damping : ndarray, shape (2, 2)
        d F / d v [N s/m], from the velocity dependence of mu.
    """

    force: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray


class PlanarState(NamedTuple):
    """Everything worth recording about a (trial or committed) 2D state of the element.

    Vectors are (x, y) arrays of shape (2,): displacement [m], velocity [m/s], force and
    friction_force [N], z [-]; the rest are floats in SI units.
    """

    time: float
    displacement: np.ndarray
    velocity: np.ndarray
    force: np.ndarray
    friction_force: np.ndarray
    z: np.ndarray
    mu: float
    temperature: float
    heat_flux: float
    axial_load: float


def _vector(value: ArrayLike, name: str) -> np.ndarray:
    array = np.asarray(value, dtype=float)
    if array.shape != (2,) or not np.all(np.isfinite(array)):
        raise ValueError(f"The {name!r} parameter of BidirectionalElement.set_trial must be a "
                         f"finite (x, y) pair. Got {value!r} instead.")
    return array


class BidirectionalElement:
    """Stateful bidirectional DCFPB element: set_trial / commit / revert.

    Parameters
    ----------
    bearing : DCFPBearing
        The bearing's parameters (those of the planar element).
    grid_orientation : float or None
        Orientation of the precise model's monitor grid [deg]; None (the default) follows the
        motion (:class:`~isolator.bidirectional.heating.MonitorGrid`). Ignored by the other models.
    """

    def __init__(self, bearing: DCFPBearing, grid_orientation: float | None = None) -> None:
        if not isinstance(bearing, DCFPBearing):
            raise TypeError(f"The 'bearing' parameter of BidirectionalElement must be a "
                            f"DCFPBearing. Got {bearing!r} instead.")
        self.bearing = bearing
        self._friction = bind_plate_friction(bearing.friction, bearing.contact_radius,
                                             bearing.displacement_capacity, grid_orientation)
        self._radius = bearing.effective_radius
        self._spherical = bearing.restoring == "spherical"
        self._yield = bearing.yield_displacement
        friction = bearing.friction
        t0 = (friction.thermal.initial_temperature if isinstance(friction, PTVFriction)
              else friction.initial_temperature)
        n0 = bearing.axial_load_at(0.0)
        zero = np.zeros(2)
        mu0 = (self._friction.trial(zero, zero, n0 / bearing.contact_area, 0.0).mu
               if n0 > 0 else 0.0)
        self._friction.revert()
        self._committed = PlanarState(0.0, zero, zero, zero, zero, zero, mu0, t0, 0.0, n0)
        self._trial = self._committed

    @property
    def committed(self) -> PlanarState:
        """The last committed state."""
        return self._committed

    @property
    def trial_state(self) -> PlanarState:
        """The state of the last trial (equals the committed state after commit/revert)."""
        return self._trial

    @property
    def friction_state(self):
        """The bound 2D friction evaluator (gives access to the heating model)."""
        return self._friction

    def _restoring(self, u: np.ndarray, n: float, time: float) -> tuple[np.ndarray, np.ndarray]:
        if math.isinf(self._radius):
            return np.zeros(2), np.zeros((2, 2))
        if self._spherical:
            squared = self._radius**2 - float(u @ u)
            if not squared > 0.0:
                raise trial_failure(self.bearing, math.hypot(*u), time, f"at the effective "
                                    f"radius {self._radius!r} m of the spherical law")
            root = math.sqrt(squared)
            return n * u / root, n * (_IDENTITY / root + np.outer(u, u) / root**3)
        return n * u / self._radius, (n / self._radius) * _IDENTITY

    def set_trial(self, displacement: ArrayLike, velocity: ArrayLike, time: float,
                  axial_load: float | None = None) -> PlanarTrial:
        """Force and tangents at a trial displacement [m], velocity [m/s] (both (x, y)) and
        time [s].

        ``axial_load`` [N], when given, is the compressive load of this trial instead of the
        bearing's own (``DCFPBearing.axial_load_at(time)``): a building in plan computes it
        per bearing and per trial (gravity share, vertical motion, overturning). Zero or
        negative is uplift, as for the bearing's own load. The tangents are taken at fixed
        load.

        Raises
        ------
        ValueError
            If ``time`` is before the last committed time, or a vector is not a finite pair.
        dcfpb.common.errors.CapacityExceeded
            If the model cannot evaluate the displacement (the slider off the monitor grid,
            at the spherical law's radius).
        """
        u = _vector(displacement, "displacement")
        v = _vector(velocity, "velocity")
        c = self._committed
        dt = time - c.time
        if dt < 0.0:
            raise ValueError(f"The trial time {time!r} s of BidirectionalElement.set_trial is "
                             f"before the last committed time {c.time!r} s.")
        n = self.bearing.axial_load_at(time) if axial_load is None else float(axial_load)
        z, dz_du = isotropic_return_map(c.z, u - c.displacement, self._yield)
        try:
            if n <= 0.0:  # uplift: no contact, no force, no heat; the plates cool
                friction = self._friction.lifted(u, dt)
            else:
                friction = self._friction.trial(u, v, n / self.bearing.contact_area, dt)
        except CapacityExceeded as error:
            raise trial_failure(self.bearing, math.hypot(*u), time, str(error)) from None
        if n <= 0.0:
            restoring, stiffness, n = np.zeros(2), np.zeros((2, 2)), 0.0
        else:
            restoring, stiffness = self._restoring(u, n, time)
        friction_force = friction.mu * n * z
        force = restoring + friction_force
        self._trial = PlanarState(time, u, v, force, friction_force, z, friction.mu,
                                  friction.temperature, friction.heat_flux, n)
        return PlanarTrial(force, stiffness + friction.mu * n * dz_du,
                           n * np.outer(z, friction.dmu_dvelocity))

    def commit(self) -> None:
        """Accept the last trial: its state becomes the committed state, its heat is added."""
        self._friction.commit()
        self._committed = self._trial

    def revert(self) -> None:
        """Drop the last trial and return to the committed state exactly."""
        self._friction.revert()
        self._trial = self._committed


def bidirectional_element(bearing: DCFPBearing, *,
                          grid_orientation: float | None = None) -> BidirectionalElement:
    """A new bidirectional element of ``bearing`` at rest (u = 0, z = 0, t = 0), unheated.

    See :class:`BidirectionalElement`.
    """
    return BidirectionalElement(bearing, grid_orientation)
