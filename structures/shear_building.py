"""A shear building on an isolation level, in one direction or in plan: storey masses and
stiffnesses, superstructure damping, and its matrices on the levels' degrees of freedom.

Each floor has L degrees of freedom relative to the base (L = 1: u_x; L = 3 with a
:class:`~structures.plan.Plan`: u_x, u_y, theta at the centre of stiffness); on isolators the
base slab, level 0, comes first. The superstructure acts on the storey drifts only,
``T = [-I | I]``: ``K = T^T K_fb T``, ``C = T^T C_fb T``, so it neither resists nor damps a
rigid-body motion on the isolators, whose forces
:class:`~structures.isolated_building.IsolatedShearBuilding` adds.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np
import scipy.linalg

from dcfpb.common.errors import InputError, InputTypeError
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_array, check_choice, check_int, check_real
from structures.model import LinearModel
from structures.plan import (
    Plan,
    axial_distribution,
    bearing_stiffness_matrix,
    gravity_shares,
    level_mass_matrix,
)

__all__ = [
    "ModalDamping",
    "ModalProperties",
    "RayleighDamping",
    "ShearBuilding",
    "modal_analysis",
    "shear_stiffness_matrix",
]

_PROFILES = ("uniform", "triangular", "storey_shear")
DIRECTIONS = ("x", "y")
"""The horizontal directions, in their order."""


class ModalProperties(NamedTuple):
    """Undamped modes, sorted from the longest period: ``periods`` (m,) [s] (``inf`` for a mode
    with no stiffness) and mass-normalised ``shapes`` as columns (m, m) [kg^-1/2]
    (``shapes.T @ M @ shapes = I``), each signed so that its top-floor component is positive."""

    periods: np.ndarray
    shapes: np.ndarray

    @property
    def circular_frequencies(self) -> np.ndarray:
        """Natural circular frequencies ``2 pi / T`` [rad/s]."""
        return 2.0 * np.pi / self.periods


def shear_stiffness_matrix(storey_stiffnesses: np.ndarray) -> np.ndarray:
    """Tridiagonal stiffness matrix (n, n) [N/m] of a fixed-base shear building with the lateral
    ``storey_stiffnesses`` (n,) [N/m] from the bottom up (storey i joins floors i-1 and i)."""
    k = np.asarray(storey_stiffnesses, dtype=float)
    above = np.append(k[1:], 0.0)
    return np.diag(k + above) - np.diag(k[1:], 1) - np.diag(k[1:], -1)


def modal_analysis(mass: np.ndarray, stiffness: np.ndarray) -> ModalProperties:
    """Periods and mass-normalised shapes from ``K phi = omega^2 M phi``, for a symmetric
    positive definite ``mass`` [kg] and a symmetric ``stiffness`` [N/m] matrix of shape (m, m)."""
    omega_squared, shapes = scipy.linalg.eigh(stiffness, mass)
    omega = np.sqrt(np.clip(omega_squared, 0.0, None))
    with np.errstate(divide="ignore"):
        periods = 2.0 * np.pi / omega  # inf for a mode without stiffness
    top = shapes[-1, :]
    largest = shapes[np.argmax(np.abs(shapes), axis=0), np.arange(shapes.shape[1])]
    reference = np.where(np.abs(top) > 1e-12 * np.abs(largest), top, largest)
    return ModalProperties(periods, shapes * np.sign(reference))


@dataclass(frozen=True)
class RayleighDamping:
    """Rayleigh damping ``C = a0 M + a1 K`` with the damping ``ratios`` [-], each in [0, 1), at
    two distinct fixed-base ``modes`` (1-based)."""

    ratios: tuple[float, float] = (0.02, 0.02)
    modes: tuple[int, int] = (1, 2)

    def __post_init__(self) -> None:
        owner = type(self).__name__
        pairs = (self.ratios, self.modes)
        if any(not isinstance(x, tuple | list) or len(x) != 2 for x in pairs):
            raise InputError(
                f"The 'ratios' and 'modes' parameters of {owner} must hold two values each. "
                f"Got {self.ratios!r} and {self.modes!r} instead."
            )
        ratios = tuple(
            check_real(r, "ratios", owner, low=0.0, high=1.0, high_open=True) for r in self.ratios
        )
        modes = tuple(check_int(m, "modes", owner, low=1) for m in self.modes)
        if modes[0] == modes[1]:
            raise InputError(
                f"The 'modes' parameter of {owner} must hold two distinct mode numbers. "
                f"Got {self.modes!r} instead."
            )
        object.__setattr__(self, "ratios", ratios)
        object.__setattr__(self, "modes", modes)

    def check(self, n_modes: int) -> None:
        """Raise if the building has fewer than ``max(modes)`` modes."""
        if max(self.modes) > n_modes:
            raise InputError(
                f"The 'modes' parameter of RayleighDamping must be mode numbers in [1, {n_modes}] "
                f"for a {n_modes}-storey building (use ModalDamping for a single storey). "
                f"Got {self.modes!r} instead."
            )

    @staticmethod
    def coefficients(
        circular_frequencies: tuple[float, float], ratios: tuple[float, float]
    ) -> tuple[float, float]:
        """Return ``(a0 [1/s], a1 [s])`` so that ``xi(omega) = a0/(2 omega) + a1 omega/2``."""
        wi, wj = circular_frequencies
        xi, xj = ratios
        denominator = wj**2 - wi**2
        a0 = 2.0 * wi * wj * (xi * wj - xj * wi) / denominator
        a1 = 2.0 * (xj * wj - xi * wi) / denominator
        return a0, a1

    def matrix(self, mass: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
        """Damping matrix [N s/m] for the given mass [kg] and stiffness [N/m] matrices."""
        self.check(mass.shape[0])
        omega = modal_analysis(mass, stiffness).circular_frequencies
        i, j = self.modes
        a0, a1 = self.coefficients((omega[i - 1], omega[j - 1]), self.ratios)
        return a0 * mass + a1 * stiffness


@dataclass(frozen=True)
class ModalDamping:
    """Classical damping with a ratio in every fixed-base mode,
    ``C = M Phi diag(2 xi_i omega_i) Phi^T M`` with the mass-normalised shapes ``Phi``: one
    ``ratio`` for every mode, or one per mode from the first, each in [0, 1) [-]."""

    ratio: float | tuple[float, ...] = 0.02

    def __post_init__(self) -> None:
        owner = type(self).__name__

        def checked(ratio: object) -> float:
            return check_real(ratio, "ratio", owner, low=0.0, high=1.0, high_open=True)

        if isinstance(self.ratio, tuple | list | np.ndarray):
            value: float | tuple[float, ...] = tuple(map(checked, self.ratio))
        else:
            value = checked(self.ratio)
        object.__setattr__(self, "ratio", value)

    def check(self, n_modes: int) -> None:
        """Raise if per-mode ratios do not number ``n_modes``."""
        if isinstance(self.ratio, tuple) and len(self.ratio) != n_modes:
            raise InputError(
                f"The 'ratio' parameter of ModalDamping must hold {n_modes} per-mode ratios for "
                f"a {n_modes}-storey building. Got {len(self.ratio)} instead."
            )

    def matrix(self, mass: np.ndarray, stiffness: np.ndarray) -> np.ndarray:
        """Damping matrix [N s/m] for the given mass [kg] and stiffness [N/m] matrices."""
        self.check(mass.shape[0])
        periods, shapes = modal_analysis(mass, stiffness)
        modal = 2.0 * np.asarray(self.ratio) * (2.0 * np.pi / periods)
        mode_mass = mass @ shapes
        damping = (mode_mass * modal) @ mode_mass.T
        return 0.5 * (damping + damping.T)


_DEFAULT_DAMPING = RayleighDamping()


def _frozen(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


@dataclass(frozen=True, eq=False)
class ShearBuilding:
    """A shear building on a fixed base or on an isolation level, in one direction or, with a
    :class:`~structures.plan.Plan`, in plan (degrees of freedom: module docstring).

    In plan each level is a rigid diaphragm (:func:`~structures.plan.level_mass_matrix`),
    storey ``s`` joins levels ``s-1`` and ``s`` with ``k_x``, ``k_y`` and ``k_theta`` at the
    centre of stiffness, and the ground translates without turning. Rayleigh damping takes
    ``a0, a1`` from the fixed-base modes along x and applies them in plan; modal damping in
    plan takes one ratio for every mode.

    Parameters
    ----------
    floor_masses : array_like
        Floor masses from the first floor up, shape (n,) [kg].
    storey_stiffnesses : array_like
        Lateral storey stiffnesses along x from the first storey up, shape (n,) [N/m].
    base_mass : float
        Mass of the base slab above the isolators [kg].
    damping : RayleighDamping or ModalDamping
        Damping of the superstructure, defined on the fixed-base building (default
        ``RayleighDamping()``: 2 % at modes 1 and 2).
    plan : Plan, optional
        The building in plan (None: in one direction).

    Raises
    ------
    InputError
        For a value outside its range; with a plan, a plan that does not fit the building (a
        per-storey field of another length, an inertia or torsional stiffness with neither its
        value nor the plan's dimensions), bearings that cannot carry the weight
        (:func:`~structures.plan.gravity_shares`), or per-mode modal damping ratios.
    """

    floor_masses: np.ndarray
    storey_stiffnesses: np.ndarray
    base_mass: float
    damping: RayleighDamping | ModalDamping = _DEFAULT_DAMPING
    plan: Plan | None = None

    def __post_init__(self) -> None:
        owner = type(self).__name__
        masses = check_array(self.floor_masses, "floor_masses", owner, low=0.0, low_open=True)
        stiffnesses = check_array(
            self.storey_stiffnesses, "storey_stiffnesses", owner, low=0.0, low_open=True
        )
        if stiffnesses.shape != masses.shape:
            raise InputError(
                f"The 'storey_stiffnesses' parameter of {owner} must have one value per floor "
                f"({masses.shape[0]}). Got {stiffnesses.shape[0]} instead."
            )
        base = check_real(self.base_mass, "base_mass", owner, low=0.0, low_open=True)
        if not isinstance(self.damping, RayleighDamping | ModalDamping):
            raise InputTypeError(
                f"The 'damping' parameter of {owner} must be a RayleighDamping or ModalDamping. "
                f"Got {self.damping!r} instead."
            )
        self.damping.check(masses.shape[0])
        object.__setattr__(self, "floor_masses", _frozen(masses.copy()))
        object.__setattr__(self, "storey_stiffnesses", _frozen(stiffnesses.copy()))
        object.__setattr__(self, "base_mass", base)
        if self.plan is not None:
            if not isinstance(self.plan, Plan):
                raise InputTypeError(f"The 'plan' parameter of {owner} must be a Plan or None. "
                                     f"Got {self.plan!r} instead.")
            if isinstance(self.damping, ModalDamping) and isinstance(self.damping.ratio, tuple):
                raise InputError(
                    f"The 'damping' of a {owner} in plan must be RayleighDamping or "
                    "ModalDamping with one ratio for every mode (the mode numbers of one "
                    f"direction do not name the modes in plan). Got {self.damping!r} instead.")
            _ = self.storey_table, self.level_inertias, self.gravity_shares  # checked now

    @classmethod
    def from_period(
        cls,
        floor_masses: object,
        fixed_base_period: float,
        *,
        base_mass: float,
        profile: str | object = "uniform",
        damping: RayleighDamping | ModalDamping = _DEFAULT_DAMPING,
        plan: Plan | None = None,
    ) -> ShearBuilding:
        """The building whose fixed-base period along x is ``fixed_base_period`` [s], its storey
        stiffnesses [N/m] a scaled ``profile``: ``"uniform"``, ``"triangular"`` (``n, ..., 1``
        from the bottom up), ``"storey_shear"`` (proportional to the mass each storey carries)
        or a positive (n,) array. The other arguments are the class's."""
        owner = f"{cls.__name__}.from_period"
        masses = check_array(floor_masses, "floor_masses", owner, low=0.0, low_open=True)
        target = check_real(fixed_base_period, "fixed_base_period", owner, low=0.0, low_open=True)
        n = masses.shape[0]
        if isinstance(profile, str):
            shape = {
                "uniform": np.ones(n),
                "triangular": np.arange(n, 0, -1, dtype=float),
                "storey_shear": np.cumsum(masses[::-1])[::-1],
            }[check_choice(profile, "profile", owner, _PROFILES)]
        else:
            shape = check_array(profile, "profile", owner, low=0.0, low_open=True)
            if shape.shape != (n,):
                raise InputError(
                    f"The 'profile' parameter of {owner} must have one value per floor ({n}). "
                    f"Got {shape.shape[0]} instead."
                )
        period = modal_analysis(np.diag(masses), shear_stiffness_matrix(shape)).periods[0]
        return cls(masses, shape * (period / target) ** 2, base_mass, damping, plan)

    @property
    def n_storeys(self) -> int:
        """Number of storeys (and floors above the base) [-]."""
        return int(self.floor_masses.shape[0])

    @property
    def level_dofs(self) -> int:
        """Degrees of freedom per level: 1 (x) in one direction, 3 (x, y, theta) in plan."""
        return 1 if self.plan is None else 3

    @property
    def directions(self) -> tuple[str, ...]:
        """The horizontal directions the building moves in: ``("x",)`` or ``("x", "y")``."""
        return DIRECTIONS[:1] if self.plan is None else DIRECTIONS

    @property
    def n_dof(self) -> int:
        """Degrees of freedom on the isolators, (n + 1) per level [-]."""
        return self.level_dofs * (self.n_storeys + 1)

    @property
    def total_mass(self) -> float:
        """Mass carried by the isolators: base slab plus floors [kg]."""
        return float(self.base_mass + self.floor_masses.sum())

    @property
    def weight(self) -> float:
        """Weight carried by the isolators [N]."""
        return self.total_mass * STANDARD_GRAVITY

    @cached_property
    def bearing_positions(self) -> np.ndarray:
        """Bearing positions (n_b, 2) [m]: the plan's, or the reference point in one direction."""
        if self.plan is None:
            return _frozen(np.zeros((1, 2)))
        return self.plan.bearing_coordinates

    @cached_property
    def level_masses(self) -> np.ndarray:
        """Masses of the base slab and the floors, shape (n+1,) [kg]."""
        return _frozen(np.concatenate([[self.base_mass], self.floor_masses]))

    @cached_property
    def level_centres(self) -> np.ndarray:
        """Centres of mass of the base slab and the floors, (n+1, 2) [m] (0 in one direction)."""
        if self.plan is None:
            return _frozen(np.zeros((self.n_storeys + 1, 2)))
        floors = self.plan.floor_eccentricities(self.n_storeys)
        return _frozen(np.vstack([self.plan.base_eccentricity, floors]))

    @cached_property
    def level_inertias(self) -> np.ndarray:
        """Mass moments of inertia about each level's centre of mass, (n+1,) [kg m^2] (plan)."""
        floors, base = self._plan("level_inertias").inertias(self.floor_masses, self.base_mass)
        return _frozen(np.concatenate([[base], floors]))

    @cached_property
    def storey_table(self) -> np.ndarray:
        """Storey stiffnesses per level degree of freedom, shape (n, level_dofs): ``k_x``, or
        ``(k_x, k_y, k_theta)`` in plan [N/m, N/m, N m/rad]."""
        if self.plan is None:
            return _frozen(self.storey_stiffnesses[:, None].copy())
        return _frozen(self.plan.stiffnesses(self.storey_stiffnesses))

    @cached_property
    def gravity_shares(self) -> np.ndarray:
        """Each bearing position's share of the weight, (n_b,) [N] (all of it in one direction):
        from the levels' centres of mass, or from the plan's ``load_eccentricity`` if given."""
        if self.plan is None:
            return _frozen(np.array([self.weight]))
        loads = self.plan.load_centres(self.n_storeys)  # held where the masses moved
        return _frozen(gravity_shares(self.plan.bearing_coordinates, self.level_masses,
                                      self.level_centres if loads is None else loads))

    @cached_property
    def axial_distribution(self) -> np.ndarray:
        """``G`` of :func:`structures.plan.axial_distribution`, shape (n_b, 3) (plan)."""
        return _frozen(axial_distribution(self._plan("axial_distribution").bearing_coordinates))

    def _plan(self, what: str) -> Plan:
        if self.plan is None:
            raise InputError(f"The {what!r} of a ShearBuilding need its plan; this one has none.")
        return self.plan

    def _level_masses(self, levels: range) -> np.ndarray:
        if self.plan is None:
            return np.diag(self.level_masses[levels.start:levels.stop])
        out = np.zeros((3 * len(levels), 3 * len(levels)))
        for k, level in enumerate(levels):
            out[3 * k:3 * k + 3, 3 * k:3 * k + 3] = level_mass_matrix(
                self.level_masses[level], self.level_inertias[level], self.level_centres[level])
        return out

    @cached_property
    def fixed_base_mass_matrix(self) -> np.ndarray:
        """Fixed-base mass matrix of the floors, (n L, n L) [kg, kg m, kg m^2]."""
        return _frozen(self._level_masses(range(1, self.n_storeys + 1)))

    @cached_property
    def fixed_base_stiffness_matrix(self) -> np.ndarray:
        """Fixed-base stiffness matrix, shape (n L, n L) [N/m, N m/rad]."""
        table, dofs = self.storey_table, self.level_dofs
        n = self.n_storeys
        out = np.zeros((dofs * n, dofs * n))
        for component in range(dofs):
            out[component::dofs, component::dofs] = shear_stiffness_matrix(table[:, component])
        return _frozen(out)

    @cached_property
    def fixed_base_damping_matrix(self) -> np.ndarray:
        """Fixed-base (superstructure) damping matrix, shape (n L, n L) [N s/m, ...]."""
        mass, stiffness = self.fixed_base_mass_matrix, self.fixed_base_stiffness_matrix
        if self.plan is not None and isinstance(self.damping, RayleighDamping):
            along_x = modal_analysis(np.diag(self.floor_masses),
                                     shear_stiffness_matrix(self.storey_stiffnesses))
            omega = along_x.circular_frequencies
            i, j = self.damping.modes
            a0, a1 = self.damping.coefficients((omega[i - 1], omega[j - 1]), self.damping.ratios)
            return _frozen(a0 * mass + a1 * stiffness)
        return _frozen(self.damping.matrix(mass, stiffness))

    @cached_property
    def drift_transformation(self) -> np.ndarray:
        """``T`` with ``T q`` the drifts of every floor from the base slab, (n L, (n+1) L)."""
        n, dofs = self.n_storeys, self.level_dofs
        return _frozen(np.hstack([-np.tile(np.eye(dofs), (n, 1)), np.eye(dofs * n)]))

    @cached_property
    def isolated_mass_matrix(self) -> np.ndarray:
        """Mass matrix on the levels' degrees of freedom, base slab first, ((n+1) L, (n+1) L)."""
        return _frozen(self._level_masses(range(self.n_storeys + 1)))

    @cached_property
    def isolated_stiffness_matrix(self) -> np.ndarray:
        """Superstructure stiffness ``T^T K_fb T`` (isolators not included) [N/m, ...]."""
        t = self.drift_transformation
        return _frozen(t.T @ self.fixed_base_stiffness_matrix @ t)

    @cached_property
    def isolated_damping_matrix(self) -> np.ndarray:
        """Superstructure damping ``T^T C_fb T`` on the drifts only [N s/m, ...]."""
        t = self.drift_transformation
        return _frozen(t.T @ self.fixed_base_damping_matrix @ t)

    @cached_property
    def isolated_influence(self) -> np.ndarray:
        """Ground-motion influence: ones, shape (n+1,), in one direction; ``R`` of the (x, y)
        ground acceleration, shape (3 (n+1), 2), in plan [-]."""
        if self.plan is None:
            return _frozen(np.ones(self.n_storeys + 1))
        r = np.zeros((self.n_dof, 2))
        r[0::3, 0] = 1.0
        r[1::3, 1] = 1.0
        return _frozen(r)

    def fixed_base_modes(self) -> ModalProperties:
        """Periods [s] and mass-normalised shapes of the fixed-base building."""
        return modal_analysis(self.fixed_base_mass_matrix, self.fixed_base_stiffness_matrix)

    def isolated_modes(self, isolator_stiffness: float | np.ndarray) -> ModalProperties:
        """Periods [s] and mass-normalised shapes on linear isotropic isolators of lateral
        ``isolator_stiffness`` [N/m]: a total shared equally by the bearing positions (e.g.
        ``W / R_eff``), or one value per position, shape (n_b,) (e.g. ``N_i / R_eff``)."""
        return modal_analysis(self.isolated_mass_matrix, self._with_isolator(isolator_stiffness))

    def fixed_base_model(self) -> LinearModel:
        """The fixed-base building as a :class:`~structures.model.LinearModel`."""
        influence = self.isolated_influence[self.level_dofs:]
        return LinearModel(self.fixed_base_mass_matrix, self.fixed_base_damping_matrix,
                           self.fixed_base_stiffness_matrix, influence)

    def isolated_linear_model(self, isolator_stiffness: float | np.ndarray) -> LinearModel:
        """The building on linear, undamped isolators (see :meth:`isolated_modes`)."""
        return LinearModel(self.isolated_mass_matrix, self.isolated_damping_matrix,
                           self._with_isolator(isolator_stiffness), self.isolated_influence)

    def _with_isolator(self, isolator_stiffness: float | np.ndarray) -> np.ndarray:
        positions = self.bearing_positions
        owner = type(self).__name__
        if np.ndim(isolator_stiffness) == 0:
            total = check_real(isolator_stiffness, "isolator_stiffness", owner, low=0.0)
            each = np.full(len(positions), total / len(positions))
        else:
            each = check_array(isolator_stiffness, "isolator_stiffness", owner, low=0.0)
            if each.shape != (len(positions),):
                raise InputError(f"The 'isolator_stiffness' parameter of {owner} must be a "
                                 f"total or one value per bearing ({len(positions)}). Got "
                                 f"{each.shape[0]} values instead.")
        stiffness = self.isolated_stiffness_matrix.copy()
        if self.plan is None:
            stiffness[0, 0] += float(each.sum())
        else:
            stiffness[:3, :3] += bearing_stiffness_matrix(positions, each)
        return stiffness
