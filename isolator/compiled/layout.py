"""The layout of the friction constants the compiled kernels read: one specification, one packer.

The kernels take a precise or simplified friction model's constants as one float array in the
order :data:`PTV_PARAMETERS`, indexed by the named constants below (folded at compile time);
everyone fills it through :func:`pack_ptv`, so no code reads it by a bare index number."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

PTV_PARAMETERS = (
    "first_point", "spacing", "n_points", "flux_half_width", "average_over_contact",
    "initial_temperature", "flux_coefficient", "factor_code", "reference_pressure",
    "rate_parameter", "mu_t0", "use_pressure", "use_velocity", "use_temperature", "surfaces",
)
"""Order of the constants packed into the ``parameters`` array of the PTV kernels.

first_point, spacing [m], n_points, flux_half_width [m], average_over_contact (1.0/0.0)
    The monitor line of :class:`isolator.heating.SurfaceHeating` and how the contact is read.
initial_temperature [degC], flux_coefficient [degC m^2 / (W s^0.5)]
    T0 and the heat-conduction coefficient c of Eq. 4-6.
factor_code (0 paper, 1 Kumar), reference_pressure [Pa], rate_parameter [s/m], mu_t0 [-]
    The factor set and the friction coefficient at the reference condition (Eq. 1-3, 7).
use_pressure, use_velocity, use_temperature (1.0/0.0)
    Which dependencies of Eq. 7 are active.
surfaces
    Number of sliding surfaces sharing the heat (2 for a DCFPB).
"""

(
    FIRST_POINT, SPACING, N_POINTS, FLUX_HALF_WIDTH, AVERAGE_OVER_CONTACT,
    INITIAL_TEMPERATURE, FLUX_COEFFICIENT, FACTOR_CODE, REFERENCE_PRESSURE,
    RATE_PARAMETER, MU_T0, USE_PRESSURE, USE_VELOCITY, USE_TEMPERATURE, SURFACES,
) = range(len(PTV_PARAMETERS))


def pack_ptv(values: Mapping[str, float]) -> np.ndarray:
    """The ``parameters`` array of the PTV kernels from ``values``, constants named as in
    :data:`PTV_PARAMETERS` (a missing one is 0.0: a model without heating leaves the monitor
    line out). Raises ``KeyError`` for a name not in :data:`PTV_PARAMETERS`."""
    unknown = sorted(set(values) - set(PTV_PARAMETERS))
    if unknown:
        raise KeyError(f"pack_ptv: unknown constant(s) {unknown}; known: {PTV_PARAMETERS}")
    return np.array([float(values.get(name, 0.0)) for name in PTV_PARAMETERS], dtype=float)
