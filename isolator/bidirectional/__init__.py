"""The bearing in two horizontal directions: the bidirectional element
(:mod:`~isolator.bidirectional.element`, a vector friction force on a circle, the 2x2 tangents),
its friction models with the speed of the vector velocity
(:mod:`~isolator.bidirectional.friction`), the precise model's heating over a 2D monitor grid on
each plate (:mod:`~isolator.bidirectional.heating`), orbits (:mod:`~isolator.bidirectional.orbits`)
and the 2D test machine (:mod:`~isolator.bidirectional.testrig`). The compiled form of the
element is :mod:`isolator.compiled.element`.
"""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "BidirectionalElement": "isolator.bidirectional.element",
    "bidirectional_element": "isolator.bidirectional.element",
    "MonitorGrid": "isolator.bidirectional.heating",
    "Orbit": "isolator.bidirectional.orbits",
    "orbit": "isolator.bidirectional.orbits",
    "OrbitTestResult": "isolator.bidirectional.testrig",
    "run_orbit": "isolator.bidirectional.testrig",
    "run_orbit_test": "isolator.bidirectional.testrig",
}
__all__ = ["BidirectionalElement", "MonitorGrid", "Orbit", "OrbitTestResult",
           "bidirectional_element", "orbit", "run_orbit", "run_orbit_test"]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
