"""The design layer: ASCE/SEI 7-16 Chapter 17 on the package's buildings and bearings (a
workflow like :mod:`structures.suites`). Property modification (17.2.8.4,
:mod:`~structures.design.properties`), the equivalent lateral force procedure (17.5,
:mod:`~structures.design.elf`), the virtual prototype test (17.8,
:mod:`~structures.design.prototype`) and the standard's numeric limits in one table
(:mod:`~structures.design.limits`). The names in ``__all__`` are imported on first use::

    config = structures.load_config("examples/five_storey_plan.toml")
    lam = PropertyModification.overall(1.8, 0.6)
    result = elf(config, Site(S_MS=1.5, S_M1=0.6), lam, R=2.0)
    print(result.table())
"""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

_EXPORTS = {
    "LIMITS": "structures.design.limits",
    "Limit": "structures.design.limits",
    "B_M_TABLE": "structures.design.limits",
    "damping_coefficient": "structures.design.limits",
    "limits_table": "structures.design.limits",
    "PropertyModification": "structures.design.properties",
    "Site": "structures.design.elf",
    "ELFResult": "structures.design.elf",
    "elf": "structures.design.elf",
    "nominal_mu": "structures.design.elf",
    "response_modification": "structures.design.elf",
    "PrototypeResult": "structures.design.prototype",
    "prototype_test": "structures.design.prototype",
}
__all__ = [
    "B_M_TABLE",
    "LIMITS",
    "ELFResult",
    "Limit",
    "PropertyModification",
    "PrototypeResult",
    "Site",
    "damping_coefficient",
    "elf",
    "limits_table",
    "nominal_mu",
    "prototype_test",
    "response_modification",
]
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, globals())
