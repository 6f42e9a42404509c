"""What a Chapter 17 design analysis returns (:func:`structures.design.design`): the ELF, the
response-history runs at both bounds and every mass position, their averages and envelope,
the checks with their clauses, and the data the report's figures are drawn from.

Every number is in SI units; the unit of each peak column is in :data:`PEAK_UNITS`. The report
(``dcfpb design``) renders these objects and computes nothing of its own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dcfpb.common.files import json_safe

__all__ = ["PEAK_UNITS", "Check", "DesignResult", "PairInfo", "ScaledSpectra", "Table"]

PEAK_UNITS: dict[str, str] = {
    "isolator_displacement": "m",      # resultant, largest over the bearings
    "centre_displacement": "m",        # resultant of the base slab at the centre of rigidity
    "corner_displacement": "m",        # resultant of the bearing farthest from the centre
    "corner_centre_ratio": "-",        # corner_displacement / centre_displacement
    "isolator_displacement_x": "m",    # largest |u_x| over the bearings
    "isolator_displacement_y": "m",
    "base_shear_x": "N",               # below the isolation interface (V_b), per direction
    "base_shear_y": "N",
    "storey_shear_x": "N",             # first storey above the interface (V_s), per direction
    "storey_shear_y": "N",
    "max_drift_ratio_x": "-",          # largest storey drift / storey height, per direction
    "max_drift_ratio_y": "-",
    "roof_acceleration_x": "m/s^2",
    "roof_acceleration_y": "m/s^2",
    "axial_load_max": "N",             # largest compression of any bearing (positive)
    "axial_load_min": "N",             # smallest of any bearing (<= 0: uplift)
    "max_temperature": "degC",         # contact temperature, any bearing
    "mu_min": "-",                     # friction coefficient range while sliding
    "mu_max": "-",
}
"""Unit of every peak column of :attr:`DesignResult.peaks`; per-storey drift ratios are
the columns ``drift_ratio_x_1`` ... ``drift_ratio_y_n`` [-] (storey 1 the lowest)."""


@dataclass(frozen=True)
class Check:
    """One check of the standard: a demand against its limit.

    Attributes
    ----------
    key : str
        Stable key in ``design.json``, e.g. ``"rh_D_TM_vs_elf_x"``.
    clause : str
        Where the standard sets it, e.g. ``"17.6.4.4"``.
    description : str
        What is checked, in words a reviewer reads.
    demand, limit : float
        The value found and the value allowed, in ``unit``.
    unit : str
        Unit of demand and limit.
    kind : {"max", "min", "floor"}
        ``"max"``: the demand must not exceed the limit; ``"min"``: must not fall below it;
        ``"floor"``: the limit is a lower bound on the design value, not a pass/fail test
        (17.6.4.3: response-history results below the floors of 17.6.4.1-2 are scaled up to
        them), so it always passes and says which governs.
    bound, position : str
        Where the governing demand was found (``""`` where it does not apply).
    """

    key: str
    clause: str
    description: str
    demand: float
    limit: float
    unit: str
    kind: str = "max"
    bound: str = ""
    position: str = ""

    @property
    def passed(self) -> bool:
        """The demand within the limit (a floor always passes: it sets the design value)."""
        if self.kind == "floor":
            return True
        return self.demand <= self.limit if self.kind == "max" else self.demand >= self.limit

    @property
    def margin(self) -> float:
        """Relative margin [-]: positive passes, e.g. 0.12 = 12 % to spare; for a floor, how far
        the demand lies above it (negative: the floor governs)."""
        if self.limit == 0:
            return math.inf if self.passed else -math.inf
        sign = 1.0 if self.kind == "max" else -1.0
        return sign * (self.limit - self.demand) / abs(self.limit)

    @property
    def floor_governs(self) -> bool:
        """A floor above the demand: the design takes the floor."""
        return self.kind == "floor" and self.demand < self.limit

    @property
    def design_value(self) -> float:
        """For a floor, the value the design uses, max(demand, limit); else the demand."""
        return max(self.demand, self.limit) if self.kind == "floor" else self.demand

    @property
    def scale_up(self) -> float:
        """For a floor, the factor the response-history results are scaled up by (17.6.4.3),
        at least 1 [-]; 1 for other checks."""
        if not self.floor_governs:
            return 1.0
        return self.limit / self.demand if self.demand > 0 else math.inf

    def to_dict(self) -> dict[str, Any]:
        """For JSON."""
        return {"key": self.key, "clause": self.clause, "description": self.description,
                "demand": json_safe(self.demand), "limit": json_safe(self.limit), "unit": self.unit,
                "kind": self.kind, "bound": self.bound, "position": self.position,
                "passed": self.passed, "margin": json_safe(self.margin),
                "floor_governs": self.floor_governs, "design_value": json_safe(self.design_value),
                "scale_up": json_safe(self.scale_up)}


@dataclass(frozen=True)
class Table:
    """A table of the report: title, clause, column names with units, rows of values."""

    title: str
    clause: str
    columns: tuple[str, ...]
    units: tuple[str, ...]
    rows: tuple[tuple[Any, ...], ...]
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        """For JSON."""
        return {"title": self.title, "clause": self.clause, "columns": list(self.columns),
                "units": list(self.units), "rows": [[json_safe(v) for v in r] for r in self.rows],
                "note": self.note}


@dataclass(frozen=True)
class PairInfo:
    """One ground-motion pair of the suite.

    Attributes
    ----------
    name : str
    synthetic : bool
        Generated by the package (:func:`groundmotions.synthetic_pair`) to complete the suite.
    scale_factor : float
        Factor applied to both components [-].
    sources : tuple of str
        The files read (empty for a synthetic pair), or the generator and its seed.
    """

    name: str
    synthetic: bool
    scale_factor: float
    sources: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """For JSON."""
        return {"name": self.name, "synthetic": self.synthetic,
                "scale_factor": self.scale_factor, "sources": list(self.sources)}


@dataclass(frozen=True)
class ScaledSpectra:
    """The suite's scaling (17.3.3): target and scaled RotD100 spectra over the period range.

    Attributes
    ----------
    periods : ndarray
        Periods [s].
    target : ndarray
        MCE_R target pseudo-acceleration [g].
    pairs : dict of str to ndarray
        Each pair's RotD100 of the scaled pair [g].
    period_range : tuple of float
        0.75 T_M (upper bound) to 1.25 T_M (lower bound) [s].
    """

    periods: np.ndarray
    target: np.ndarray
    pairs: dict[str, np.ndarray]
    period_range: tuple[float, float]

    @property
    def average(self) -> np.ndarray:
        """The suite's average RotD100 [g]."""
        return np.mean(np.vstack(list(self.pairs.values())), axis=0)

    def to_dict(self) -> dict[str, Any]:
        """For JSON."""
        return {"periods": json_safe(self.periods), "target": json_safe(self.target),
                "pairs": {k: json_safe(v) for k, v in self.pairs.items()},
                "period_range": list(self.period_range), "unit": "g"}


@dataclass(frozen=True)
class DesignResult:
    """A Chapter 17 analysis of one building.

    Attributes
    ----------
    name : str
        The building's name.
    elf : ELFResult
        The equivalent lateral force procedure at both bounds (17.5).
    pairs : tuple of PairInfo
        The suite in run order.
    compliant_suite : bool
        At least the number of pairs 17.3.2 asks (false only with ``allow_fewer``).
    spectra : ScaledSpectra
        The scaling.
    peaks : pandas.DataFrame
        One row per run: ``pair``, ``synthetic``, ``bound`` (``"upper"``/``"lower"``),
        ``position`` (e.g. ``"+x"``, ``"-x"``, ``"+y"``, ``"-y"``), ``status`` and the columns
        of :data:`PEAK_UNITS` and the per-storey drift ratios.
    averages : pandas.DataFrame
        The mean over pairs of each peak column, one row per (bound, position).
    envelope : dict of str to dict
        Per peak column, the governing average ``{"value", "unit", "bound", "position"}``
        (largest; smallest for ``axial_load_min`` and ``mu_min``).
    checks : tuple of Check
        Every check, with its clause.
    tables : tuple of Table
        The report's tables in order.
    governing_run : xarray.Dataset or None
        The full result of the run that governs the isolator displacement (its corner
        bearing's orbit, temperature and hysteresis), with floor spectra where computed.
    notes : tuple of str
        Warnings and remarks for the report (non-compliance, synthetic pairs, large scale
        factors, heating double count, ...).
    options : dict
        The options of the analysis (site, lambda, R, positions, storage, ...), for JSON.
    """

    name: str
    elf: Any
    pairs: tuple[PairInfo, ...]
    compliant_suite: bool
    spectra: ScaledSpectra
    peaks: Any
    averages: Any
    envelope: dict[str, dict[str, Any]]
    checks: tuple[Check, ...]
    tables: tuple[Table, ...]
    governing_run: Any = None
    notes: tuple[str, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)

    @property
    def passed(self) -> bool:
        """Every check passes and the suite is compliant."""
        return self.compliant_suite and all(c.passed for c in self.checks)

    def to_dict(self) -> dict[str, Any]:
        """Every number of the report, keyed (``design.json``)."""
        return {
            "name": self.name, "passed": self.passed, "compliant_suite": self.compliant_suite,
            "options": {k: json_safe(v) for k, v in self.options.items()},
            "elf": self.elf.to_dict(), "pairs": [p.to_dict() for p in self.pairs],
            "spectra": self.spectra.to_dict(),
            "averages": json_safe(self.averages.to_dict(orient="records")),
            "envelope": json_safe(self.envelope), "checks": [c.to_dict() for c in self.checks],
            "tables": [t.to_dict() for t in self.tables], "notes": list(self.notes),
            "units": dict(PEAK_UNITS),
        }
