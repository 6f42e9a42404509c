"""Isolator layer: friction laws, frictional heating, the DCFPB element in one or two
directions, bearing tests (imposed histories and orbits) and their force-deflection
characteristics; the compiled element in :mod:`isolator.compiled`, the diagnosis of the
sim-to-real gap in :mod:`isolator.diagnosis`. The names in ``__all__`` are imported on first use
(the element's kernels import numba).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "DCFPBearing": "isolator.bearing",
    "AxialLoadHistory": "isolator.bearing",
    "BearingElement": "isolator.bearing",
    "ConstantFriction": "isolator.friction",
    "PTVFriction": "isolator.friction",
    "eq7": "isolator.friction",
    "MonitorLine": "isolator.heating",
    "CentrePoint": "isolator.heating",
    "ThermalProperties": "isolator.heating",
    "PaperFactors": "isolator.factors",
    "KumarFactors": "isolator.factors",
    "friction_model": "isolator.experiments",
    "protocol_bearing": "isolator.experiments",
    "ImposedHistory": "isolator.protocols",
    "sine": "isolator.protocols",
    "asce7_prototype_sequence": "isolator.protocols",
    "wind_cycles": "isolator.protocols",
    "run_test": "isolator.testrig",
    "BearingTestResult": "isolator.testrig",
    "CycleCharacteristics": "isolator.characteristics",
    "cycle_characteristics": "isolator.characteristics",
    "BearingState": "isolator.bearing",
    "FrictionModel": "isolator.friction",
    "MonitorGrid": "isolator.monitor_grid",
    "Orbit": "isolator.orbits",
    "orbit": "isolator.orbits",
    "run_orbit": "isolator.testrig",
}
__all__ = [
    "AxialLoadHistory",
    "BearingElement",
    "BearingState",
    "BearingTestResult",
    "CentrePoint",
    "ConstantFriction",
    "CycleCharacteristics",
    "DCFPBearing",
    "FrictionModel",
    "ImposedHistory",
    "KumarFactors",
    "MonitorGrid",
    "MonitorLine",
    "Orbit",
    "PTVFriction",
    "PaperFactors",
    "ThermalProperties",
    "asce7_prototype_sequence",
    "cycle_characteristics",
    "eq7",
    "friction_model",
    "orbit",
    "protocol_bearing",
    "run_orbit",
    "run_test",
    "sine",
    "wind_cycles",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())

if TYPE_CHECKING:
    from isolator.bearing import AxialLoadHistory, BearingElement, BearingState, DCFPBearing
    from isolator.characteristics import CycleCharacteristics, cycle_characteristics
    from isolator.experiments import friction_model, protocol_bearing
    from isolator.factors import KumarFactors, PaperFactors
    from isolator.friction import ConstantFriction, FrictionModel, PTVFriction, eq7
    from isolator.heating import CentrePoint, MonitorLine, ThermalProperties
    from isolator.monitor_grid import MonitorGrid
    from isolator.orbits import Orbit, orbit
    from isolator.protocols import ImposedHistory, asce7_prototype_sequence, sine, wind_cycles
    from isolator.testrig import BearingTestResult, run_orbit, run_test
