"""The design layer: ASCE/SEI 7-16 Chapter 17 on the package's buildings and bearings (a
workflow like :mod:`structures.suites`). Property modification (17.2.8.4,
:mod:`~structures.design.properties`), the equivalent lateral force procedure (17.5,
:mod:`~structures.design.elf`), the virtual prototype test (17.8,
:mod:`~structures.design.prototype`) and the standard's numeric limits in one table
(:mod:`~structures.design.limits`)::

    config = structures.load_config("examples/five_storey_plan.toml")
    lam = PropertyModification.overall(1.8, 0.6)
    result = elf(config, Site(S_MS=1.5, S_M1=0.6), lam, R=2.0)
    print(result.table())
    rh = design(config, "pairs.csv", Site(1.5, 0.6), lam, R=2.0, complete_with_synthetic=True)
    print([(c.key, c.passed, round(c.margin, 3)) for c in rh.checks])

The response-history analysis of 17.6 with 17.3 (:func:`~structures.design.response.design`)
runs suites, so its module sits a layer above :mod:`structures.suites`.
"""

from __future__ import annotations

from dcfpb.common.lazy import lazy_exports

# Imported at once, not lazily as the other packages' names: the function ``elf`` shares its
# name with the module ``structures.design.elf``, and a lazy name would lose to the submodule
# once anything imports it (Python sets the package attribute to the module).
from structures.design.elf import ELFResult, Site, elf, nominal_mu, response_modification
from structures.design.limits import (
    B_M_TABLE,
    LIMITS,
    Limit,
    damping_coefficient,
    limits_table,
)
from structures.design.properties import PropertyModification
from structures.design.prototype import PrototypeResult, prototype_test
from structures.design.result import PEAK_UNITS, Check, DesignResult, PairInfo, ScaledSpectra, Table

__all__ = [
    "B_M_TABLE",
    "LIMITS",
    "PEAK_UNITS",
    "Check",
    "DesignResult",
    "ELFResult",
    "Limit",
    "PairInfo",
    "PropertyModification",
    "PrototypeResult",
    "ScaledSpectra",
    "Site",
    "Table",
    "damping_coefficient",
    "design",
    "elf",
    "limits_table",
    "nominal_mu",
    "period_range",
    "prototype_test",
    "response_modification",
    "scaling_period_range",
]

# design() runs suites: its module is a layer above structures.suites (tests/unit/test_layers.py),
# so it is imported on first use, not here.
__getattr__, __dir__ = lazy_exports(__name__, {
    "building_design": "structures.design.response", "design": "structures.design.response",
    "period_range": "structures.design.response",
    "scaling_period_range": "structures.design.response"}, globals())
