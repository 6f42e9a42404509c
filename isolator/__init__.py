"""Isolator layer: friction laws, frictional heating, the DCFPB element, bearing tests, the
force-deflection characteristics and the diagnosis of the sim-to-real gap
(:mod:`isolator.diagnosis`); the compiled element and its kernels in :mod:`isolator.compiled`.

The names in ``__all__`` are importable from the package (on first use: the element's kernels
import numba)::

    from isolator import DCFPBearing, PTVFriction, MonitorLine, run_test, sine
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
    "BidirectionalElement": "isolator.bidirectional.element",
    "bidirectional_element": "isolator.bidirectional.element",
    "MonitorGrid": "isolator.bidirectional.heating",
    "Orbit": "isolator.bidirectional.orbits",
    "orbit": "isolator.bidirectional.orbits",
    "OrbitTestResult": "isolator.bidirectional.testrig",
    "run_orbit": "isolator.bidirectional.testrig",
    "run_orbit_test": "isolator.bidirectional.testrig",
}
__all__ = [
    "AxialLoadHistory",
    "BearingElement",
    "BearingTestResult",
    "BidirectionalElement",
    "CentrePoint",
    "ConstantFriction",
    "CycleCharacteristics",
    "DCFPBearing",
    "ImposedHistory",
    "KumarFactors",
    "MonitorGrid",
    "MonitorLine",
    "Orbit",
    "OrbitTestResult",
    "PTVFriction",
    "PaperFactors",
    "ThermalProperties",
    "asce7_prototype_sequence",
    "bidirectional_element",
    "cycle_characteristics",
    "eq7",
    "friction_model",
    "orbit",
    "protocol_bearing",
    "run_orbit",
    "run_orbit_test",
    "run_test",
    "sine",
    "wind_cycles",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())

if TYPE_CHECKING:
    from isolator.bearing import AxialLoadHistory, BearingElement, DCFPBearing
    from isolator.bidirectional.element import BidirectionalElement, bidirectional_element
    from isolator.bidirectional.heating import MonitorGrid
    from isolator.bidirectional.orbits import Orbit, orbit
    from isolator.bidirectional.testrig import OrbitTestResult, run_orbit, run_orbit_test
    from isolator.characteristics import CycleCharacteristics, cycle_characteristics
    from isolator.experiments import friction_model, protocol_bearing
    from isolator.factors import KumarFactors, PaperFactors
    from isolator.friction import ConstantFriction, PTVFriction, eq7
    from isolator.heating import CentrePoint, MonitorLine, ThermalProperties
    from isolator.protocols import ImposedHistory, asce7_prototype_sequence, sine, wind_cycles
    from isolator.testrig import BearingTestResult, run_test
