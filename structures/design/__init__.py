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
"""

from __future__ import annotations

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
