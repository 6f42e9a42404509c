"""A shear building on an isolation level: storey masses and stiffnesses, superstructure damping.

The fixed-base building has one lateral DOF per floor, ``u_1 ... u_n`` relative to its base.
On isolators it gains the base slab: DOFs ``[u_b, u_1, ..., u_n]``, all relative to the ground.
The superstructure matrices act on the storey drifts only, through the transformation
``T = [-1 | I]`` (``u_i - u_b``): ``K = T^T K_fb T`` and ``C = T^T C_fb T``. Hence a rigid-body
motion of the whole building on its isolators is neither resisted nor damped by the
superstructure, and the isolation level gets no viscous damping from it (``C @ 1 = 0``): the
isolator brings its own force, added by the model that couples the two.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np
import scipy.linalg

from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import check_array, check_choice, check_int, check_real
from structures.model import LinearModel

__all__ = [
    "ModalDamping",
    "ModalProperties",
    "RayleighDamping",
    "ShearBuilding",
    "modal_analysis",
    "shear_stiffness_matrix",
]

_PROFILES = ("uniform", "triangular", "storey_shear")


class ModalProperties(NamedTuple):
    """Undamped modes, sorted from the longest period.

    Attributes
    ----------
    periods : numpy.ndarray
        Natural periods, shape (m,) [s] (``inf`` for a mode with no stiffness).
    shapes : numpy.ndarray
        Mass-normalised mode shapes as columns (``shapes.T @ M @ shapes = I``), shape (m, m)
        [kg^-1/2]; each signed so that its top-floor component is positive.
    """

    periods: np.ndarray
    shapes: np.ndarray

    @property
    def circular_frequencies(self) -> np.ndarray:
        """Natural circular frequencies ``2 pi / T`` [rad/s]."""
        return 2.0 * np.pi / self.periods


def shear_stiffness_matrix(storey_stiffnesses: np.ndarray) -> np.ndarray:
    """Stiffness matrix of a fixed-base shear building (storey ``i`` joins floors ``i-1``, ``i``).

    Parameters
    ----------
    storey_stiffnesses : numpy.ndarray
        Lateral storey stiffnesses from the bottom up, shape (n,) [N/m].

    Returns
    -------
    numpy.ndarray
        Tridiagonal stiffness matrix, shape (n, n) [N/m].
    """
    k = np.asarray(storey_stiffnesses, dtype=float)
    above = np.append(k[1:], 0.0)
    return np.diag(k + above) - np.diag(k[1:], 1) - np.diag(k[1:], -1)


def modal_analysis(mass: np.ndarray, stiffness: np.ndarray) -> ModalProperties:
    """Solve ``K phi = omega^2 M phi`` for the periods and mass-normalised shapes.

    Parameters
    ----------
    mass, stiffness : numpy.ndarray
        Symmetric mass [kg] (positive definite) and stiffness [N/m] matrices, shape (m, m).
    """
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
    """Rayleigh damping ``C = a0 M + a1 K`` with given ratios at two fixed-base modes.

    Parameters
    ----------
    ratios : tuple of float
        Damping ratios at the two modes, each in [0, 1) [-].
    modes : tuple of int
        The two (distinct, 1-based) fixed-base mode numbers where the ratios hold.
    """

    ratios: tuple[float, float] = (0.02, 0.02)
    modes: tuple[int, int] = (1, 2)

    def __post_init__(self) -> None:
        owner = type(self).__name__
        pairs = (self.ratios, self.modes)
        if any(not isinstance(x, tuple | list) or len(x) != 2 for x in pairs):
            raise ValueError(
                f"The 'ratios' and 'modes' parameters of {owner} must hold two values each. "
                f"Got {self.ratios!r} and {self.modes!r} instead."
            )
        ratios = tuple(
            check_real(r, "ratios", owner, low=0.0, high=1.0, high_open=True) for r in self.ratios
        )
        modes = tuple(check_int(m, "modes", owner, low=1) for m in self.modes)
        if modes[0] == modes[1]:
            raise ValueError(
                f"The 'modes' parameter of {owner} must hold two distinct mode numbers. "
                f"Got {self.modes!r} instead."
            )
        object.__setattr__(self, "ratios", ratios)
        object.__setattr__(self, "modes", modes)

    def check(self, n_modes: int) -> None:
        """Raise if the building has fewer than ``max(modes)`` modes."""
        if max(self.modes) > n_modes:
            raise ValueError(
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
    """Classical damping with a given ratio in every fixed-base mode.

    ``C = M Phi diag(2 xi_i omega_i) Phi^T M`` with mass-normalised shapes ``Phi``.

    Parameters
    ----------
    ratio : float or tuple of float
        One damping ratio for every mode, or one per mode (first mode first), in [0, 1) [-].
    """

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
            raise ValueError(
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
    """A shear building that can stand on a fixed base or on an isolation level.

    Parameters
    ----------
    floor_masses : array_like
        Floor masses from the first floor up, shape (n,) [kg].
    storey_stiffnesses : array_like
        Lateral storey stiffnesses from the first storey up, shape (n,) [N/m].
    base_mass : float
        Mass of the base slab above the isolators [kg].
    damping : RayleighDamping or ModalDamping
        Damping of the superstructure, defined on the fixed-base building and applied to the
        storey drifts only, never to the isolation level.
    """

    floor_masses: np.ndarray
    storey_stiffnesses: np.ndarray
    base_mass: float
    damping: RayleighDamping | ModalDamping = _DEFAULT_DAMPING

    def __post_init__(self) -> None:
        owner = type(self).__name__
        masses = check_array(self.floor_masses, "floor_masses", owner, low=0.0, low_open=True)
        stiffnesses = check_array(
            self.storey_stiffnesses, "storey_stiffnesses", owner, low=0.0, low_open=True
        )
        if stiffnesses.shape != masses.shape:
            raise ValueError(
                f"The 'storey_stiffnesses' parameter of {owner} must have one value per floor "
                f"({masses.shape[0]}). Got {stiffnesses.shape[0]} instead."
            )
        base = check_real(self.base_mass, "base_mass", owner, low=0.0, low_open=True)
        if not isinstance(self.damping, RayleighDamping | ModalDamping):
            raise TypeError(
                f"The 'damping' parameter of {owner} must be a RayleighDamping or ModalDamping. "
                f"Got {self.damping!r} instead."
            )
        self.damping.check(masses.shape[0])
        object.__setattr__(self, "floor_masses", _frozen(masses.copy()))
        object.__setattr__(self, "storey_stiffnesses", _frozen(stiffnesses.copy()))
        object.__setattr__(self, "base_mass", base)

    @classmethod
    def from_period(
        cls,
        floor_masses: object,
        fixed_base_period: float,
        *,
        base_mass: float,
        profile: str | object = "uniform",
        damping: RayleighDamping | ModalDamping = _DEFAULT_DAMPING,
    ) -> ShearBuilding:
        """Scale a storey-stiffness profile to hit a fixed-base fundamental period.

        Periods scale as ``1 / sqrt(stiffness)``, so one scaling hits the target exactly.

        Parameters
        ----------
        floor_masses : array_like
            Floor masses from the first floor up, shape (n,) [kg].
        fixed_base_period : float
            Target fundamental period of the fixed-base building [s].
        base_mass : float
            Mass of the base slab above the isolators [kg].
        profile : {"uniform", "triangular", "storey_shear"} or array_like
            Relative storey stiffnesses: equal; ``n, n-1, ..., 1`` from the bottom up; or
            proportional to the mass carried by each storey; or a positive (n,) array.
        damping : RayleighDamping or ModalDamping
            Superstructure damping.
        """
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
                raise ValueError(
                    f"The 'profile' parameter of {owner} must have one value per floor ({n}). "
                    f"Got {shape.shape[0]} instead."
                )
        period = modal_analysis(np.diag(masses), shear_stiffness_matrix(shape)).periods[0]
        return cls(masses, shape * (period / target) ** 2, base_mass, damping)

    @property
    def n_storeys(self) -> int:
        """Number of storeys (and floors above the base) [-]."""
        return int(self.floor_masses.shape[0])

    @property
    def total_mass(self) -> float:
        """Mass carried by the isolators: base slab plus floors [kg]."""
        return float(self.base_mass + self.floor_masses.sum())

    @property
    def weight(self) -> float:
        """Weight carried by the isolators [N]."""
        return self.total_mass * STANDARD_GRAVITY

    @cached_property
    def fixed_base_mass_matrix(self) -> np.ndarray:
        """Fixed-base mass matrix, shape (n, n) [kg]."""
        return _frozen(np.diag(self.floor_masses))

    @cached_property
    def fixed_base_stiffness_matrix(self) -> np.ndarray:
        """Fixed-base stiffness matrix, shape (n, n) [N/m]."""
        return _frozen(shear_stiffness_matrix(self.storey_stiffnesses))

    @cached_property
    def fixed_base_damping_matrix(self) -> np.ndarray:
        """Fixed-base (superstructure) damping matrix, shape (n, n) [N s/m]."""
        return _frozen(
            self.damping.matrix(self.fixed_base_mass_matrix, self.fixed_base_stiffness_matrix)
        )

    @cached_property
    def drift_transformation(self) -> np.ndarray:
        """``T`` with ``T @ [u_b, u_1..u_n] = [u_1 - u_b, ..., u_n - u_b]``, shape (n, n+1)."""
        n = self.n_storeys
        return _frozen(np.hstack([-np.ones((n, 1)), np.eye(n)]))

    @cached_property
    def isolated_mass_matrix(self) -> np.ndarray:
        """Mass matrix on DOFs ``[u_b, u_1..u_n]``, shape (n+1, n+1) [kg]."""
        return _frozen(np.diag(np.concatenate([[self.base_mass], self.floor_masses])))

    @cached_property
    def isolated_stiffness_matrix(self) -> np.ndarray:
        """Superstructure stiffness ``T^T K_fb T`` (isolator not included), (n+1, n+1) [N/m]."""
        t = self.drift_transformation
        return _frozen(t.T @ self.fixed_base_stiffness_matrix @ t)

    @cached_property
    def isolated_damping_matrix(self) -> np.ndarray:
        """Superstructure damping ``T^T C_fb T`` on drifts only, (n+1, n+1) [N s/m]."""
        t = self.drift_transformation
        return _frozen(t.T @ self.fixed_base_damping_matrix @ t)

    @cached_property
    def isolated_influence(self) -> np.ndarray:
        """Ground-motion influence vector on ``[u_b, u_1..u_n]`` (all ones), (n+1,) [-]."""
        return _frozen(np.ones(self.n_storeys + 1))

    def fixed_base_modes(self) -> ModalProperties:
        """Periods [s] and mass-normalised shapes of the fixed-base building."""
        return modal_analysis(self.fixed_base_mass_matrix, self.fixed_base_stiffness_matrix)

    def isolated_modes(self, isolator_stiffness: float) -> ModalProperties:
        """Periods [s] and mass-normalised shapes on a linear isolator.

        Parameters
        ----------
        isolator_stiffness : float
            Total lateral stiffness of the isolation level [N/m] (e.g. ``W / R_eff`` of a
            friction pendulum, or an effective stiffness).
        """
        return modal_analysis(self.isolated_mass_matrix, self._with_isolator(isolator_stiffness))

    def fixed_base_model(self) -> LinearModel:
        """The fixed-base building as a :class:`~structures.model.LinearModel`."""
        return LinearModel(
            self.fixed_base_mass_matrix,
            self.fixed_base_damping_matrix,
            self.fixed_base_stiffness_matrix,
            np.ones(self.n_storeys),
        )

    def isolated_linear_model(self, isolator_stiffness: float) -> LinearModel:
        """The building on a linear, undamped isolator of the given stiffness [N/m]."""
        return LinearModel(
            self.isolated_mass_matrix,
            self.isolated_damping_matrix,
            self._with_isolator(isolator_stiffness),
            self.isolated_influence,
        )

    def _with_isolator(self, isolator_stiffness: float) -> np.ndarray:
        k = check_real(isolator_stiffness, "isolator_stiffness", type(self).__name__, low=0.0)
        stiffness = self.isolated_stiffness_matrix.copy()
        stiffness[0, 0] += k
        return stiffness
