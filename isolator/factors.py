"""Dependency factors of the friction coefficient on pressure, velocity and temperature.

Two sets, chosen by name with :func:`factor_set`: ``"paper"``, the SSB paper's Eq. 1-3
(Nishimoto et al. 2016; Nakamura et al. 2015), and ``"kumar"``, Kumar, Whittaker & Constantinou
(2015) as in OpenSees ``FPBearingPTV``. Arguments are SI (Pa, m/s, degC; the paper's N/mm^2 and
mm/s are converted here only); every factor returns ``(value, derivative)`` with respect to the
SI argument (for velocity, the speed |v|). The ``*_raw`` kernels take floats or arrays and
compile with numba.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dcfpb.common.units import MM_PER_M, PA_PER_N_PER_MM2
from dcfpb.common.validation import check_choice, check_real

ArrayLike = float | np.ndarray


def paper_pressure_raw(pressure):
    """Eq. 1 on a pressure [Pa]: (gamma, d gamma / d p [1/Pa])."""
    sigma = pressure / PA_PER_N_PER_MM2
    power = 2.03 * sigma**-0.19
    return power + 0.068, -0.19 * power / sigma / PA_PER_N_PER_MM2  # Eq. 1


def paper_velocity_raw(speed):
    """Eq. 2 on a speed [m/s]: (alpha, d alpha / d|v| [s/m])."""
    decay = 0.55 * np.exp(-0.019 * MM_PER_M * speed)
    return 1.0 - decay, 0.019 * MM_PER_M * decay  # Eq. 2


def paper_temperature_raw(temperature):
    """Eq. 3 on a temperature [degC]: (beta, d beta / d T [1/degC])."""
    beta = 1.13 * np.exp(-0.007 * temperature)
    return beta, -0.007 * beta  # Eq. 3


def kumar_pressure_raw(pressure, reference_pressure):
    """kp = 0.7^((p - p_ref) / 50 MPa) and its derivative [1/Pa], p and p_ref in [Pa]."""
    kp = np.exp(np.log(0.7) * (pressure - reference_pressure) / 50.0e6)
    return kp, kp * np.log(0.7) / 50.0e6


def kumar_velocity_raw(speed, rate_parameter):
    """kv = 1 - 0.5 exp(-a |v|) and its derivative [s/m], |v| in [m/s] and a in [s/m]."""
    decay = 0.5 * np.exp(-rate_parameter * speed)
    return 1.0 - decay, rate_parameter * decay


def kumar_temperature_raw(temperature):
    """kT = 0.789 (0.7^(T / 50) + 0.4) and its derivative [1/degC], T in [degC]."""
    power = np.exp(np.log(0.7) * temperature / 50.0)
    return 0.789 * (power + 0.4), 0.789 * power * np.log(0.7) / 50.0


def paper_pressure_factor(pressure: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
    """Pressure factor gamma = 2.03 sigma^-0.19 + 0.068 [-] of Eq. 1 (sigma in N/mm^2) and its
    derivative [1/Pa] at a contact pressure > 0 [Pa] (float or array); 1.0004 at 60 N/mm^2."""
    gamma, dgamma = paper_pressure_raw(np.asarray(pressure, dtype=float))
    return _scalar(gamma), _scalar(dgamma)


def paper_velocity_factor(speed: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
    """Velocity factor alpha = 1 - 0.55 exp(-0.019 v) [-] of Eq. 2 (v in mm/s) and its derivative
    [s/m] at a sliding speed |v| [m/s] (float or array); 0.45 at rest, 0.9997 at 400 mm/s."""
    alpha, dalpha = paper_velocity_raw(np.abs(np.asarray(speed, dtype=float)))
    return _scalar(alpha), _scalar(dalpha)


def paper_temperature_factor(temperature: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
    """Temperature factor beta = 1.13 exp(-0.007 T) [-] of Eq. 3 and its derivative [1/degC] at
    a contact temperature T [degC] (float or array); 0.982, not 1, at 20 degC."""
    beta, dbeta = paper_temperature_raw(np.asarray(temperature, dtype=float))
    return _scalar(beta), _scalar(dbeta)


@dataclass(frozen=True)
class PaperFactors:
    """The SSB paper's dependency factors (Eq. 1-3); no parameters."""

    name: str = "paper"

    @property
    def kernel_parameters(self) -> tuple[int, float, float]:
        """(set code, reference pressure, rate parameter) for the compiled kernels."""
        return 0, 0.0, 0.0

    def pressure(self, pressure: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
        """Eq. 1, see :func:`paper_pressure_factor`."""
        return paper_pressure_factor(pressure)

    def velocity(self, speed: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
        """Eq. 2, see :func:`paper_velocity_factor`."""
        return paper_velocity_factor(speed)

    def temperature(self, temperature: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
        """Eq. 3, see :func:`paper_temperature_factor`."""
        return paper_temperature_factor(temperature)


@dataclass(frozen=True)
class KumarFactors:
    """Kumar et al. (2015) dependency factors, as in OpenSees ``FPBearingPTV``.

    Parameters
    ----------
    reference_pressure : float
        Pressure p_ref at which kp = 1 [Pa]; default 60 MPa (the paper's reference).
    rate_parameter : float
        Rate parameter a of kv = 1 - 0.5 exp(-a v) [s/m]; default 100 s/m.

    References
    ----------
    Kumar M., Whittaker A.S., Constantinou M.C. (2015). Characterizing friction in sliding
    isolation bearings. Earthquake Engng Struct. Dyn. 44, 1409-1425.
    """

    reference_pressure: float = 60.0e6
    rate_parameter: float = 100.0
    name: str = "kumar"

    def __post_init__(self) -> None:
        owner = type(self).__name__
        check_real(self.reference_pressure, "reference_pressure", owner, low=0.0, low_open=True)
        check_real(self.rate_parameter, "rate_parameter", owner, low=0.0, low_open=True)

    @property
    def kernel_parameters(self) -> tuple[int, float, float]:
        """(set code, reference pressure, rate parameter) for the compiled kernels."""
        return 1, float(self.reference_pressure), float(self.rate_parameter)

    def pressure(self, pressure: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
        """kp = 0.7^((p - p_ref) / 50 MPa) and its derivative [1/Pa]."""
        kp, dkp = kumar_pressure_raw(np.asarray(pressure, dtype=float), self.reference_pressure)
        return _scalar(kp), _scalar(dkp)

    def velocity(self, speed: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
        """kv = 1 - 0.5 exp(-a |v|) and its derivative with respect to |v| [s/m]."""
        kv, dkv = kumar_velocity_raw(np.abs(np.asarray(speed, dtype=float)), self.rate_parameter)
        return _scalar(kv), _scalar(dkv)

    def temperature(self, temperature: ArrayLike) -> tuple[ArrayLike, ArrayLike]:
        """kT = 0.789 (0.7^(T / 50) + 0.4) and its derivative [1/degC]."""
        kt, dkt = kumar_temperature_raw(np.asarray(temperature, dtype=float))
        return _scalar(kt), _scalar(dkt)


FACTOR_SETS = {"paper": PaperFactors, "kumar": KumarFactors}


def factor_set(name: str, **parameters: float) -> PaperFactors | KumarFactors:
    """The factor set called ``name``, ``"paper"`` (Eq. 1-3) or ``"kumar"`` (OpenSees
    FPBearingPTV), made with ``parameters`` (Kumar's ``reference_pressure`` [Pa] and
    ``rate_parameter`` [s/m])."""
    check_choice(name, "name", "factor_set", tuple(FACTOR_SETS))
    return FACTOR_SETS[name](**parameters)


def _scalar(x: np.ndarray) -> ArrayLike:
    """A Python float for a 0-d array, so that scalar callers stay scalar."""
    return float(x) if np.ndim(x) == 0 else x
