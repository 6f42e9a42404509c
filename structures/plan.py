"""The plan of an isolated building: where its bearings stand and where its masses sit.

Coordinates x, y [m] are taken from the reference point ``O``, the centre of stiffness of every
storey (all on one vertical line): the bearings stand at ``(x_i, y_i)``, each floor's centre of
mass at its eccentricity ``(e_x, e_y)`` (the base slab's at ``base_eccentricity``). The rigid
base on equally stiff bearings shares a vertical resultant and its moments linearly over them
(:func:`axial_distribution`); the weight's shares are :func:`gravity_shares`, from the centres of
mass, or from ``load_eccentricity`` where the masses are moved without their loads (the
accidental mass eccentricity of a design analysis, :meth:`Plan.shifted`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_array, check_real

__all__ = ["Plan", "axial_distribution", "bearing_stiffness_matrix", "bearing_transformation",
           "gravity_shares", "level_mass_matrix"]

_OWNER = "Plan"
_LARGEST = 1e4  # [m]: the largest plan coordinate or dimension accepted


def _frozen(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


def _pairs(value: object, name: str, rows: int | None = None) -> np.ndarray:
    """An (m, 2) array of finite coordinates [m] within +-10 km."""
    array = np.asarray(value, dtype=float)
    if array.ndim != 2 or array.shape[1] != 2 or (rows is not None and array.shape[0] != rows):
        count = "m" if rows is None else str(rows)
        raise InputError(f"The {name!r} parameter of {_OWNER} must be a ({count}, 2) array of "
                         f"(x, y) coordinates [m]. Got shape {array.shape} instead.")
    check_array(array, name, _OWNER, ndim=2, low=-_LARGEST, high=_LARGEST)
    return _frozen(array.copy())


def _positive(value: object, name: str, high: float) -> np.ndarray:
    array = check_array(np.atleast_1d(np.asarray(value, dtype=float)), name, _OWNER, low=0.0,
                        low_open=True, high=high)
    return _frozen(array.copy())


def axial_distribution(coordinates: np.ndarray) -> np.ndarray:
    """``G``, shape (n_b, 3) [1, 1/m, 1/m], sharing a vertical resultant ``F_z`` [N] and its
    moments ``S_x = sum N x``, ``S_y = sum N y`` [N m] linearly over bearings at ``coordinates``
    (n_b, 2) [m]: ``N = G @ (F_z, S_x, S_y)`` [N], ``G = A^T (A A^T)^-1``, ``A = [1; x; y]``.

    Raises
    ------
    InputError
        If the bearings lie on one line (fewer than three, or colinear).
    """
    xy = np.asarray(coordinates, dtype=float)
    a = np.vstack([np.ones(xy.shape[0]), xy.T])
    normal = a @ a.T
    scatter = normal[1:, 1:] - np.outer(normal[0, 1:], normal[0, 1:]) / normal[0, 0]
    spread = np.linalg.eigvalsh(scatter)  # second moments about the centroid [m^2]
    size = max(float(np.max(np.abs(xy))), 1.0)
    if xy.shape[0] < 3 or spread[0] <= 1e-12 * size**2 * xy.shape[0]:
        raise InputError(
            f"The 'bearing_coordinates' parameter of {_OWNER} must hold at least 3 bearings not "
            f"all on one line, so that the base can carry the weight and the overturning "
            f"moments about both axes. Got {xy.tolist()!r} instead.")
    return a.T @ np.linalg.inv(normal)


def gravity_shares(coordinates: np.ndarray, masses: np.ndarray,
                   centres: np.ndarray) -> np.ndarray:
    """Each bearing's share of the weight by the statics of the rigid base, ``N_i`` (n_b,) [N]
    summing to ``W = g sum(masses)``, for bearings at ``coordinates`` (n_b, 2) [m] carrying the
    ``masses`` (m,) [kg] (base slab and floors) whose centres of mass are ``centres`` (m, 2) [m].

    Raises
    ------
    InputError
        If the bearings lie on one line, or a share is not positive (the centre of mass too far
        from the bearings' centroid), naming the bearing and the centre of mass.
    """
    weights = STANDARD_GRAVITY * np.asarray(masses, dtype=float)
    total = float(weights.sum())
    moments = weights @ np.asarray(centres, dtype=float)
    shares = axial_distribution(coordinates) @ np.array([total, *moments])
    low = int(np.argmin(shares))
    if shares[low] <= 0.0:
        xg, yg = moments / total
        x, y = np.asarray(coordinates, dtype=float)[low]
        raise InputError(
            f"The plan cannot carry the weight: with the centre of mass at ({xg:.4g}, {yg:.4g}) "
            f"m bearing {low} at ({x:.4g}, {y:.4g}) m would take {shares[low]:.4g} N of the "
            f"weight {total:.4g} N. The 'eccentricity' and 'bearing_coordinates' of {_OWNER} "
            "must put the centre of mass where every bearing's gravity share is positive "
            "(well inside the bearings' outline).")
    return shares


@dataclass(frozen=True, eq=False)
class Plan:
    """The plan of a building on isolators (coordinates: module docstring).

    Parameters
    ----------
    bearing_coordinates : array_like
        Bearing positions ``(x_i, y_i)``, shape (n_b, 2) [m], in [-10000, 10000]; at least 3,
        not on one line.
    eccentricity : array_like
        Centre of mass of the floors ``(e_x, e_y)`` [m]: one pair for every floor, shape (2,),
        or one per floor from the first up, shape (n, 2).
    dimensions : tuple of float, optional
        Dimensions ``(a, b)`` of a rectangular plan along x and y [m], in (0, 10000]: the default
        of the inertias (``m (a^2 + b^2) / 12``) and of the torsional stiffness.
    floor_inertias, base_inertia : array_like, float, optional
        Mass moments of inertia of each floor, shape (n,), and of the base slab about their own
        centres of mass [kg m^2], > 0; by default from ``dimensions``.
    base_eccentricity : array_like
        Centre of mass of the base slab ``(e_x, e_y)`` [m].
    storey_stiffnesses_y : array_like, optional
        Storey stiffnesses along y, first storey up, shape (n,) [N/m], > 0; by default those
        along x.
    torsional_stiffnesses : array_like, optional
        Torsional storey stiffnesses, shape (n,) [N m/rad], > 0; by default the lateral ones
        spread uniformly over the rectangle ``a x b``: ``(k_x b^2 + k_y a^2) / 12``.
    storey_heights : float or array_like, optional
        Storey heights, one for all or one per storey [m], in (0, 1000]: the lever arms of the
        overturning (required when it is modelled).
    load_eccentricity : array_like, optional
        The centres ``(x, y)`` [m] the bearings' gravity loads are shared from, when they are
        not those of the masses: one pair for every level, shape (2,), or one per level, base
        slab first, shape (n+1, 2). None (default): the loads follow the masses (a real
        offset). Given, the masses sit at ``eccentricity`` and ``base_eccentricity`` (their
        inertia and torsion) while the loads stay where this says: the accidental mass
        eccentricity of ASCE 7-16 17.6.2 as a design moves the mass, not the building's weight
        on its bearings (:meth:`shifted`).

    Raises
    ------
    InputError
        For a value of the wrong shape or outside its range, naming the field.
    """

    bearing_coordinates: np.ndarray
    eccentricity: np.ndarray = (0.0, 0.0)  # type: ignore[assignment]
    dimensions: tuple[float, float] | None = None
    floor_inertias: np.ndarray | None = None
    base_inertia: float | None = None
    base_eccentricity: np.ndarray = (0.0, 0.0)  # type: ignore[assignment]
    storey_stiffnesses_y: np.ndarray | None = None
    torsional_stiffnesses: np.ndarray | None = None
    storey_heights: float | np.ndarray | None = None
    load_eccentricity: np.ndarray | None = None

    def __post_init__(self) -> None:
        fields: dict[str, object] = {
            "bearing_coordinates": _pairs(self.bearing_coordinates, "bearing_coordinates")}
        axial_distribution(fields["bearing_coordinates"])  # colinear bearings: an error now
        eccentricity = np.asarray(self.eccentricity, dtype=float)
        fields["eccentricity"] = _pairs(eccentricity.reshape(1, 2) if eccentricity.shape == (2,)
                                        else eccentricity, "eccentricity")
        fields["base_eccentricity"] = _pairs(np.reshape(self.base_eccentricity, (1, -1)),
                                             "base_eccentricity", 1)[0]
        if self.dimensions is not None:
            dims = _positive(self.dimensions, "dimensions", _LARGEST)
            if dims.shape != (2,):
                raise InputError(f"The 'dimensions' parameter of {_OWNER} must be the plan's "
                                 f"(a, b) along x and y [m]. Got {self.dimensions!r} instead.")
            fields["dimensions"] = (float(dims[0]), float(dims[1]))
        for name, high in (("floor_inertias", 1e16), ("storey_stiffnesses_y", 1e15),
                           ("torsional_stiffnesses", 1e20), ("storey_heights", 1000.0)):
            if getattr(self, name) is not None:
                fields[name] = _positive(getattr(self, name), name, high)
        if self.load_eccentricity is not None:
            load = np.asarray(self.load_eccentricity, dtype=float)
            fields["load_eccentricity"] = _pairs(load.reshape(1, 2) if load.shape == (2,)
                                                 else load, "load_eccentricity")
        if self.base_inertia is not None:
            fields["base_inertia"] = check_real(self.base_inertia, "base_inertia", _OWNER,
                                                low=0.0, low_open=True, high=1e16)
        for name, value in fields.items():
            object.__setattr__(self, name, value)

    @property
    def n_bearings(self) -> int:
        """Number of bearings [-]."""
        return int(self.bearing_coordinates.shape[0])

    def _per_storey(self, name: str, n: int) -> np.ndarray:
        value = getattr(self, name)
        if value.shape == (1,) and name == "storey_heights":
            return np.full(n, value[0])
        if value.shape != (n,):
            raise InputError(f"The {name!r} parameter of {_OWNER} must hold one value per "
                             f"storey ({n}). Got {value.shape[0]} instead.")
        return value

    def _rectangle(self, name: str) -> tuple[float, float]:
        if self.dimensions is None:
            raise InputError(f"The {name!r} parameter of {_OWNER} is needed when 'dimensions' "
                             "(the rectangle (a, b) [m] it defaults from) is not given.")
        return self.dimensions

    def floor_eccentricities(self, n: int) -> np.ndarray:
        """Centre of mass of each floor, shape (n, 2) [m]."""
        if self.eccentricity.shape[0] == 1:
            return np.repeat(self.eccentricity, n, axis=0)
        if self.eccentricity.shape[0] != n:
            raise InputError(f"The 'eccentricity' parameter of {_OWNER} must be one (e_x, e_y) "
                             f"pair or one per floor ({n}). Got {self.eccentricity.shape[0]} "
                             "pairs instead.")
        return self.eccentricity

    def load_centres(self, n: int) -> np.ndarray | None:
        """The centres the gravity loads of the base slab and the ``n`` floors are shared from,
        (n+1, 2) [m], or None where the loads follow the masses."""
        if self.load_eccentricity is None:
            return None
        if self.load_eccentricity.shape[0] == 1:
            return np.repeat(self.load_eccentricity, n + 1, axis=0)
        if self.load_eccentricity.shape[0] != n + 1:
            raise InputError(f"The 'load_eccentricity' parameter of {_OWNER} must be one (x, y) "
                             f"pair or one per level, base slab first ({n + 1}). Got "
                             f"{self.load_eccentricity.shape[0]} pairs instead.")
        return self.load_eccentricity

    def shifted(self, offset: tuple[float, float], n: int, *, hold_loads: bool = True) -> Plan:
        """The plan with the centre of mass of every level (base slab and the ``n`` floors)
        moved by ``offset`` (dx, dy) [m]: with ``hold_loads`` the bearings' gravity loads stay
        shared from the centres before the move (``load_eccentricity``; those already held are
        kept), else they follow the masses."""
        dx, dy = (check_real(v, "offset", f"{_OWNER}.shifted", low=-_LARGEST, high=_LARGEST)
                  for v in offset)
        move = np.array([dx, dy])
        floors = self.floor_eccentricities(n) + move
        loads = None
        if hold_loads:
            held = self.load_centres(n)
            loads = (np.vstack([self.base_eccentricity, self.floor_eccentricities(n)])
                     if held is None else held)
        return dataclasses.replace(self, eccentricity=floors,
                                   base_eccentricity=self.base_eccentricity + move,
                                   load_eccentricity=loads)

    def inertias(self, floor_masses: np.ndarray, base_mass: float) -> tuple[np.ndarray, float]:
        """Mass moments of inertia about each centre of mass: floors (n,) and base [kg m^2]."""
        n = len(floor_masses)
        if self.floor_inertias is not None:
            floors = self._per_storey("floor_inertias", n)
        else:
            a, b = self._rectangle("floor_inertias")
            floors = np.asarray(floor_masses, dtype=float) * (a * a + b * b) / 12.0
        if self.base_inertia is not None:
            base = float(self.base_inertia)
        else:
            a, b = self._rectangle("base_inertia")
            base = float(base_mass) * (a * a + b * b) / 12.0
        return floors, base

    def stiffnesses(self, storey_stiffnesses_x: np.ndarray) -> np.ndarray:
        """Storey stiffnesses ``(k_x, k_y, k_theta)``, shape (n, 3) [N/m, N/m, N m/rad]."""
        kx = np.asarray(storey_stiffnesses_x, dtype=float)
        n = kx.shape[0]
        ky = kx if self.storey_stiffnesses_y is None else self._per_storey(
            "storey_stiffnesses_y", n)
        if self.torsional_stiffnesses is not None:
            kt = self._per_storey("torsional_stiffnesses", n)
        else:
            a, b = self._rectangle("torsional_stiffnesses")
            kt = (kx * b * b + ky * a * a) / 12.0
        return np.column_stack([kx, ky, kt])

    def floor_heights(self, n: int) -> np.ndarray:
        """Height of each floor above the isolation level, shape (n,) [m]."""
        if self.storey_heights is None:
            raise InputError(f"The 'storey_heights' parameter of {_OWNER} is needed for the "
                             "overturning moment of the floors' inertia forces; give it, or "
                             "leave the overturning out (overturning=False).")
        return np.cumsum(self._per_storey("storey_heights", n))


def level_mass_matrix(mass: float, inertia: float, centre: np.ndarray) -> np.ndarray:
    """Mass matrix (3, 3) [kg, kg m, kg m^2] of a rigid level on (u_x, u_y, theta) at the
    reference point, of ``mass`` m [kg] and ``inertia`` J_G [kg m^2] about its centre of mass at
    ``centre`` e = (e_x, e_y) [m]: the Hessian of the kinetic energy
    ``m/2 [(u_x' - theta' e_y)^2 + (u_y' + theta' e_x)^2] + J_G/2 theta'^2``."""
    ex, ey = float(centre[0]), float(centre[1])
    return np.array([[mass, 0.0, -mass * ey],
                     [0.0, mass, mass * ex],
                     [-mass * ey, mass * ex, inertia + mass * (ex * ex + ey * ey)]])


def bearing_transformation(x: float, y: float) -> np.ndarray:
    """``T_i`` (2, 3): a bearing's displacement at ``(x, y)`` [m] from the base slab's
    ``(u_x, u_y, theta)``, ``u_i = (u_x - theta y, u_y + theta x)``."""
    return np.array([[1.0, 0.0, -y], [0.0, 1.0, x]])


def bearing_stiffness_matrix(coordinates: np.ndarray, stiffnesses: np.ndarray) -> np.ndarray:
    """``sum_i k_i T_i^T T_i`` (3, 3) [N/m, N, N m/rad] of isotropic linear bearings."""
    out = np.zeros((3, 3))
    for (x, y), k in zip(coordinates, stiffnesses, strict=True):
        t = bearing_transformation(x, y)
        out += k * (t.T @ t)
    return out
