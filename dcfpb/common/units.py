"""Physical constants and unit factors: the one home of every conversion constant.

SI at every public boundary (N, m, s, kg, degC, Pa); the paper's equations, in N/mm^2 and mm/s,
convert with the factors below at their own door.
"""

STANDARD_GRAVITY = 9.80665
"""Standard acceleration of gravity [m/s^2]."""

PA_PER_N_PER_MM2 = 1.0e6
"""Pascal in one N/mm^2 (= MPa) [Pa]."""

MM_PER_M = 1.0e3
"""Millimetres in one metre [-]."""

M_PER_INCH = 0.0254
"""Metres in one inch [m]."""

M_PER_FOOT = 0.3048
"""Metres in one international foot (exact; not ``12 * M_PER_INCH``, which rounds) [m]."""

KELVIN_LOOK = (250.0, 400.0)
"""Temperatures [degC] that look like kelvin where a plate's or test's starting temperature
is meant (250 degC or more before a run or a test is implausible): refused as such by building
files, ``dcfpb protocol`` and the diagnosis's data and manifests."""
