"""The virtual prototype test of ASCE/SEI 7-16 Sec. 17.8: the cyclic sequence of 17.8.2.2
(:func:`isolator.protocols.asce7_prototype_sequence`) imposed on the building's bearing with
the test rig (:func:`isolator.testrig.run_test`), and per cycle the characteristic strength and
friction coefficient and the test factor they imply.

Per complete cycle of each block (:func:`isolator.characteristics.cycle_characteristics`), with
D = (D_max - D_min) / 2 and W the bearing's axial load::

    Q_d = EDC / (4 D)        mu = Q_d / W = EDC / (4 W D)

(exact for a rigid-plastic friction loop; with a yield displacement D_y the loop's EDC is
4 Q_d (D - D_y), so Q_d is low by D_y / D, 0.2 % for 0.5 mm at 0.25 m). The nominal value is the
mean of mu over the three cycles at D_M (17.8.5 as read: nominal properties from the cycles at
the maximum displacement) and lambda_test,max / lambda_test,min are the largest and smallest
cycle's mu over it (C17.2.8.4 as read: the spread of the cycles, heating among its causes).
The same ratios over every cycle of the sequence are kept too (``all_cycles_max``,
``all_cycles_min``). The standard's wording of which cycles enter was not checked against the
text (:mod:`structures.design.limits`).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_instance, check_real
from isolator.bearing import DCFPBearing
from isolator.characteristics import cycle_characteristics
from isolator.protocols import asce7_prototype_sequence
from isolator.testrig import BearingTestResult, run_test
from structures.config import BuildingConfig
from structures.design.properties import PropertyModification

__all__ = ["PrototypeCycle", "PrototypeResult", "prototype_test"]

_OWNER = "prototype_test"
_NOMINAL_BLOCK = "1.0 D_M"
_STEPS_PER_PERIOD = 200


@dataclass(frozen=True)
class PrototypeCycle:
    """One complete cycle of the prototype sequence.

    Attributes
    ----------
    block : str
        The block's label (``"1.0 D_M"``, ``"D_TM"``, ...).
    cycle : int
        Number of the cycle in its block, from 1.
    D : float
        Half the cycle's stroke, (D_max - D_min) / 2 [m].
    EDC : float
        Energy dissipated in the cycle [J].
    Q_d : float
        Characteristic strength EDC / (4 D) [N].
    mu : float
        Q_d / W [-].
    K_eff, beta_eff : float
        Effective stiffness [N/m] and damping [-] (Eq. 10-11 of the paper, 17.8.5.1/2).
    ratio : float
        mu over the nominal mu (the mean at D_M) [-].
    peak_temperature : float
        Highest contact temperature in the cycle [degC].
    """

    block: str
    cycle: int
    D: float
    EDC: float
    Q_d: float
    mu: float
    K_eff: float
    beta_eff: float
    ratio: float
    peak_temperature: float


@dataclass(frozen=True)
class PrototypeResult:
    """The virtual prototype test and what it gives.

    Attributes
    ----------
    cycles : list of PrototypeCycle
    W : float
        Axial load of the bearing [N].
    nominal_mu : float
        Mean mu over the cycles at D_M [-].
    lambda_test_max, lambda_test_min : float
        Largest and smallest mu of the cycles at D_M over the nominal [-].
    all_cycles_max, all_cycles_min : float
        The same over every cycle of the sequence [-].
    D_M, D_TM, T_M : float
        The sequence's displacements [m] and period [s].
    test : BearingTestResult
        The histories.
    """

    cycles: list[PrototypeCycle]
    W: float
    nominal_mu: float
    lambda_test_max: float
    lambda_test_min: float
    all_cycles_max: float
    all_cycles_min: float
    D_M: float
    D_TM: float
    T_M: float
    test: BearingTestResult

    def property_modification(self, **kwargs: float) -> PropertyModification:
        """A :class:`PropertyModification` with these test factors (``kwargs``: the other
        factors, e.g. ``ae_max``)."""
        return PropertyModification(test_max=max(self.lambda_test_max, 1.0),
                                    test_min=min(self.lambda_test_min, 1.0), **kwargs)

    def to_dict(self) -> dict[str, Any]:
        """The numbers (no histories), each ``{"value", "unit"}`` where it has a unit."""
        units = {"W": "N", "nominal_mu": "-", "lambda_test_max": "-", "lambda_test_min": "-",
                 "all_cycles_max": "-", "all_cycles_min": "-", "D_M": "m", "D_TM": "m",
                 "T_M": "s"}
        out: dict[str, Any] = {k: {"value": float(getattr(self, k)), "unit": u}
                               for k, u in units.items()}
        out["cycles"] = [asdict(c) for c in self.cycles]
        out["cycle_units"] = {"D": "m", "EDC": "J", "Q_d": "N", "mu": "-", "K_eff": "N/m",
                              "beta_eff": "-", "ratio": "-", "peak_temperature": "degC"}
        return out

    def table(self) -> str:
        """Per cycle: block, cycle, D [m], EDC [kJ], Q_d [kN], mu, ratio, peak T [degC]."""
        rows = [f"virtual prototype test (ASCE/SEI 7-16 17.8.2.2): D_M = {self.D_M:.4g} m, "
                f"D_TM = {self.D_TM:.4g} m, T_M = {self.T_M:.4g} s, W = {self.W / 1e3:.5g} kN",
                f"{'block':<10} {'cycle':>5} {'D [m]':>8} {'EDC [kJ]':>10} {'Q_d [kN]':>10} "
                f"{'mu':>8} {'mu/nom':>7} {'T [degC]':>9}"]
        for c in self.cycles:
            rows.append(f"{c.block:<10} {c.cycle:>5} {c.D:>8.4f} {c.EDC / 1e3:>10.4g} "
                        f"{c.Q_d / 1e3:>10.4g} {c.mu:>8.5f} {c.ratio:>7.4f} "
                        f"{c.peak_temperature:>9.2f}")
        rows.append(f"nominal mu (mean at D_M) {self.nominal_mu:.5f}; lambda_test,max "
                    f"{self.lambda_test_max:.4f}, lambda_test,min {self.lambda_test_min:.4f} "
                    f"(all cycles {self.all_cycles_max:.4f} / {self.all_cycles_min:.4f})")
        return "\n".join(rows)


def prototype_test(
    bearing: DCFPBearing | BuildingConfig,
    D_M: float,
    D_TM: float,
    T_M: float,
    *,
    model: str | None = None,
    dt: float | None = None,
    S_M1: float | None = None,
    S_MS: float | None = None,
    B_M: float | None = None,
    item2: str = "a",
    wind_displacement: float = 0.0,
) -> PrototypeResult:
    """Run the prototype sequence of 17.8.2.2 on a bearing and report each cycle.

    Parameters
    ----------
    bearing : DCFPBearing or BuildingConfig
        The bearing, with its axial load; or a building file, whose bearing (loaded by W / n,
        friction ``model``) is tested.
    D_M, D_TM : float
        Maximum and total maximum displacement [m], 0 < D_M <= D_TM <= the bearing's
        displacement capacity (e.g. from :func:`structures.design.elf`).
    T_M : float
        Effective period at which the cycles run [s].
    model : str or None
        Friction model of a building file's bearing (default the file's).
    dt : float or None
        Time step [s] (default T_M / 200).
    S_M1, S_MS, B_M : float or None
        The number of cycles at 0.75 D_TM (30 S_M1 / (S_MS B_M), at least 10; None: 10).
    item2 : {"a", "b"}
        Option of item 2 (three cycles at each amplitude, or one continuous sequence).
    wind_displacement : float
        Amplitude of the twenty wind cycles [m] (0: none).

    Raises
    ------
    InputError
        A bad argument (named), D_TM beyond the bearing's displacement capacity, or option b
        (one cycle per amplitude), which leaves no three cycles at D_M for the nominal value.
    """
    if isinstance(bearing, BuildingConfig):
        bearing = bearing.bearing(model)
    check_instance(bearing, "bearing", _OWNER, DCFPBearing, "a DCFPBearing or BuildingConfig")
    D_M = check_real(D_M, "D_M", _OWNER, low=0.0, low_open=True)
    D_TM = check_real(D_TM, "D_TM", _OWNER, low=D_M)
    T_M = check_real(T_M, "T_M", _OWNER, low=0.0, low_open=True)
    if bearing.displacement_capacity < D_TM:
        raise InputError(f"The 'D_TM' parameter of {_OWNER} must be within the bearing's "
                         f"displacement_capacity {bearing.displacement_capacity:g} m. Got "
                         f"{D_TM:g} m instead.")
    if item2 == "b":
        raise InputError(f"The 'item2' parameter of {_OWNER} must be 'a' (three cycles at each "
                         "amplitude): option 'b' has one cycle at D_M, no nominal mean. Got "
                         "'b' instead.")
    dt = T_M / _STEPS_PER_PERIOD if dt is None else check_real(dt, "dt", _OWNER, low=0.0,
                                                                low_open=True)
    history = asce7_prototype_sequence(D_M, D_TM, T_M, dt, wind_displacement=wind_displacement,
                                       S_M1=S_M1, S_MS=S_MS, B_M=B_M, item2=item2)
    test = run_test(bearing, history.time, history.displacement, history.velocity,
                    name=history.name)
    W = bearing.axial_load_at(0.0)
    raw: list[tuple[str, int, float, float, float, float, float]] = []
    for label, start, stop in history.segments:
        if label in ("rest", "wind"):
            continue
        part = slice(start, stop)
        for c in cycle_characteristics(test.displacement[part], test.force[part],
                                       test.time[part]):
            d = 0.5 * (c.Dmax - c.Dmin)
            peak = float(np.max(test.temperature[part][c.start:c.stop]))
            raw.append((label, c.cycle, d, c.EDC, c.Keff, c.beta_eff, peak))
    at_dm = [edc / (4.0 * W * d) for label, _, d, edc, *_ in raw if label == _NOMINAL_BLOCK]
    if not at_dm:
        raise InputError(f"The sequence of {_OWNER} must hold complete cycles at D_M. Got none.")
    nominal = float(np.mean(at_dm))
    cycles = []
    for label, number, d, edc, k_eff, beta_eff, peak in raw:
        q_d = edc / (4.0 * d)
        mu = q_d / W
        cycles.append(PrototypeCycle(label, number, d, edc, q_d, mu, k_eff,
                                     beta_eff if not math.isnan(beta_eff) else float("nan"),
                                     mu / nominal, peak))
    ratios = [c.ratio for c in cycles]
    return PrototypeResult(cycles, W, nominal, max(at_dm) / nominal, min(at_dm) / nominal,
                           max(ratios), min(ratios), D_M, D_TM, T_M, test)
