"""The time-integration methods as data: Newmark's family and HHT-alpha, frozen parameter sets
(``gamma``, ``beta``, ``alpha``) over the one algorithm of :mod:`structures.integrators`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dcfpb.common.errors import InputTypeError
from dcfpb.common.validation import check_choice, check_real

__all__ = ["HHT", "METHODS", "Newmark", "as_method"]


@dataclass(frozen=True)
class Newmark:
    """Newmark's method, by default the average acceleration (trapezoidal) rule: velocity weight
    ``gamma`` in [1/2, 1] (1/2: no numerical damping), displacement weight ``beta`` in (0, 1/2]
    (1/4: average, 1/6: linear acceleration) [-]."""

    gamma: float = 0.5
    beta: float = 0.25

    def __post_init__(self) -> None:
        gamma = check_real(self.gamma, "gamma", "Newmark", low=0.5, high=1.0)
        beta = check_real(self.beta, "beta", "Newmark", low=0.0, high=0.5, low_open=True)
        object.__setattr__(self, "gamma", gamma)
        object.__setattr__(self, "beta", beta)

    @property
    def alpha(self) -> float:
        """HHT weight; zero for Newmark [-]."""
        return 0.0

    @property
    def stability_limit(self) -> float:
        """Largest stable ``omega dt`` for a linear undamped system [-] (``inf``: unconditional)."""
        if 2.0 * self.beta >= self.gamma:
            return np.inf
        return float(1.0 / np.sqrt(0.5 * self.gamma - self.beta))


@dataclass(frozen=True)
class HHT:
    """The HHT-alpha method, second order with numerical damping of the high modes: ``alpha``
    in [-1/3, 0], spectral radius ``(1 + alpha)/(1 - alpha)`` at ``dt/T -> inf``,
    ``gamma = (1 - 2 alpha)/2`` and ``beta = (1 - alpha)^2/4``."""

    alpha: float = -0.05

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "alpha", check_real(self.alpha, "alpha", "HHT", low=-1 / 3, high=0)
        )

    @property
    def gamma(self) -> float:
        """Velocity weight ``(1 - 2 alpha)/2`` [-]."""
        return 0.5 - self.alpha

    @property
    def beta(self) -> float:
        """Displacement weight ``(1 - alpha)^2/4`` [-]."""
        return 0.25 * (1.0 - self.alpha) ** 2

    @property
    def stability_limit(self) -> float:
        """HHT-alpha is unconditionally stable for alpha in [-1/3, 0]."""
        return np.inf


METHODS: dict[str, type[Newmark] | type[HHT]] = {"newmark": Newmark, "hht": HHT}
"""Method names of :func:`structures.integrators.integrate`, mapped to their classes."""


def as_method(method: object, name: str = "method", owner: str = "integrate") -> Newmark | HHT:
    """The method for a name from :data:`METHODS` (default parameters) or an instance; an
    ``InputTypeError`` naming the parameter ``name`` of ``owner`` for anything else."""
    if isinstance(method, Newmark | HHT):
        return method
    if isinstance(method, str):
        return METHODS[check_choice(method, name, owner, tuple(METHODS))]()
    raise InputTypeError(
        f"The {name!r} parameter of {owner} must be one of {tuple(METHODS)} or a Newmark or "
        f"HHT instance. Got {method!r} instead."
    )
