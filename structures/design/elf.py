"""The equivalent lateral force procedure of ASCE/SEI 7-16 Sec. 17.5 for a building on friction
pendulum bearings, at the upper and the lower bound properties (Sec. 17.2.8.4).

For each bound, with mu = lambda mu_nominal, the bearings' effective stiffness and damping at
the maximum displacement D_M (the bilinear friction pendulum: post-sliding stiffness W / R_eff,
characteristic strength mu W)::

    K_M = W / R_eff + mu W / D_M
    beta_M = EDC / (2 pi K_M D_M^2) = 4 mu W D_M / (2 pi K_M D_M^2) = 2 mu / (pi (mu + D_M / R_eff))
    T_M = 2 pi sqrt(W / (K_M g))                    (Eq. 17.5-2)
    D_M = g S_M1 T_M / (4 pi^2 B_M)                  (Eq. 17.5-1, B_M of Table 17.5-1)

iterated from D_M of the pendulum period with B_M = 1 to the fixed point. Then D_TM (Eq. 17.5-3
with P_T of Eq. 17.5-4, not less than 1.15 D_M), V_b = K_M D_M (Eq. 17.5-5), V_st =
V_b (W_s / W)^(1 - 3.5 beta_M) (the abrupt transition of a friction pendulum; 2.5 for a smooth
one), V_s = V_st / R_I with the limits of 17.5.4.3 the building gives
(the fixed-base force of Chapter 12 at T_M, 1.5 times the activation force of the sliding
system, an optional wind base shear), the vertical distribution of 17.5.5 (F_1 at the base level,
F_x = C_vx V_s with k = 14 beta_M T_fb) and the storey drifts of 17.5.6 (C_d = R_I, limit
0.015 h_sx). The lower bound governs the displacements, the upper bound the forces; the result
keeps both and the envelope. The numbers of the standard come from
:mod:`structures.design.limits` (what was verified of them is said there).

The yield (pre-sliding) displacement of the bearings is neglected (rigid-plastic friction, as the
closed forms above), and so is the effect of the vertical acceleration on W.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from dcfpb.common.errors import InputError, InputWarning, RunFailure
from dcfpb.common.units import STANDARD_GRAVITY
from dcfpb.common.validation import (
    check_array,
    check_choice,
    check_instance,
    check_int,
    check_real,
)
from isolator.experiments import MODELS
from structures.config import BuildingConfig
from structures.design.limits import LIMITS, damping_coefficient, limit
from structures.design.properties import BOUNDS, PropertyModification
from structures.shear_building import modal_analysis, shear_stiffness_matrix

__all__ = ["DirectionELF", "ELFBound", "ELFResult", "Site", "elf", "fixed_point",
           "nominal_mu", "response_modification"]

G = STANDARD_GRAVITY
_OWNER = "elf"

UNITS: dict[str, str] = {
    "lambda": "-", "mu": "-", "iterations": "-", "K_M": "N/m", "beta_M": "-", "B_M": "-",
    "T_M": "s", "D_M": "m", "V_b": "N", "V_st": "N", "V_s_formula": "N", "V_s_fixed_base": "N",
    "V_s_activation": "N", "V_s_wind": "N", "V_s": "N", "F_1": "N", "W": "N", "W_s": "N",
    "R": "-", "R_I": "-", "I_e": "-", "S_MS": "g", "S_M1": "g", "T_L": "s",
    "D_TM": "m", "D_TM_over_D_M": "-", "torsion_ratio": "-", "y": "m", "e": "m", "P_T": "-",
    "b": "m", "d": "m", "T_fb": "s", "k": "-", "heights": "m", "storey_heights": "m",
    "F": "N", "storey_shear": "N", "drift": "m", "drift_ratio": "-", "drift_limit": "-",
    "max_drift_ratio": "-", "mu_nominal": "-",
}
"""The unit of every number of the result, by key."""

CLAUSES: dict[str, str] = {
    "K_M": "17.5.3.2 (effective stiffness at D_M)", "beta_M": "17.5.3.2 (effective damping)",
    "B_M": "Table 17.5-1", "T_M": "17.5.3.2, Eq. 17.5-2", "D_M": "17.5.3.1, Eq. 17.5-1",
    "D_TM": "17.5.3.3, Eq. 17.5-3", "V_b": "17.5.4.1, Eq. 17.5-5",
    "V_st": "17.5.4.2, Eq. 17.5-7", "V_s_formula": "17.5.4.2, V_st / R_I",
    "V_s_fixed_base": "17.5.4.3 item 1", "V_s_activation": "17.5.4.3 item 3",
    "V_s_wind": "17.5.4.3 item 2", "V_s": "17.5.4.2-17.5.4.3", "R_I": "17.5.4.2",
    "F_1": "17.5.5 (base level)",
    "F_x": "17.5.5", "drift": "17.5.6",
}
"""Where each quantity comes from in ASCE/SEI 7-16 (numbering as read: see the limits)."""


@dataclass(frozen=True)
class Site:
    """The site's MCE_R spectral parameters.

    Parameters
    ----------
    S_MS, S_M1 : float
        MCE_R spectral accelerations at short periods and at 1 s, adjusted for site class [g]
        (fractions of g: 1.5 for 1.5 g), in (0, 5].
    T_L : float or None
        Long-period transition period [s] (the fixed-base limit of 17.5.4.3 only).
    """

    S_MS: float
    S_M1: float
    T_L: float | None = None

    def __post_init__(self) -> None:
        owner = "Site"
        object.__setattr__(self, "S_MS", check_real(self.S_MS, "S_MS", owner, low=0.0, high=5.0,
                                                    low_open=True))
        object.__setattr__(self, "S_M1", check_real(self.S_M1, "S_M1", owner, low=0.0, high=5.0,
                                                    low_open=True))
        if self.T_L is not None:
            object.__setattr__(self, "T_L", check_real(self.T_L, "T_L", owner, low=0.0,
                                                       high=100.0, low_open=True))

    @property
    def S_DS(self) -> float:
        """Design spectral acceleration at short periods, 2/3 S_MS [g]."""
        return limit("design_over_mce") * self.S_MS

    @property
    def S_D1(self) -> float:
        """Design spectral acceleration at 1 s, 2/3 S_M1 [g]."""
        return limit("design_over_mce") * self.S_M1


def response_modification(R: float) -> float:
    """R_I = 3/8 R, within [1, 2] (Sec. 17.5.4.2), for the superstructure's R [-] > 0."""
    R = check_real(R, "R", _OWNER, low=0.0, high=10.0, low_open=True)
    r_i = limit("R_I_factor") * R
    return float(min(max(r_i, limit("R_I_min")), limit("R_I_max")))


def nominal_mu(config: BuildingConfig, model: str | None = None) -> float:
    """The nominal friction coefficient of the building file's bearings [-]: the constant
    model's mu_c (Eq. 8); for the precise and simplified models Eq. 7 at the bearing's gravity
    pressure (W / n over the contact area), the file's design velocity (default 0.4 m/s) and the
    initial temperature (no heating: the cold, nominal value)."""
    check_instance(config, "config", _OWNER, BuildingConfig, "a BuildingConfig")
    bearing = config.bearing(model)
    friction = bearing.friction
    if hasattr(friction, "nominal_mu"):
        pressure = bearing.axial_load_at(0.0) / bearing.contact_area
        velocity = float(config.friction.get("design_velocity", 0.4))
        return float(friction.nominal_mu(pressure, velocity))
    raise InputError(f"The 'mu' parameter of {_OWNER} must be given for the friction model "
                     f"{getattr(friction, 'name', friction)!r}, whose nominal coefficient this "
                     "module does not know. Got None instead.")


def fixed_point(weight: float, radius: float, mu: float, S_M1: float, *,
                tolerance: float = 1e-12, max_iterations: int = 500
                ) -> tuple[float, float, float, float, float, int]:
    """D_M of a friction pendulum system by fixed-point iteration (module docstring).

    Parameters
    ----------
    weight : float
        W, the weight on the isolators [N] (K_M scales with it, T_M does not).
    radius : float
        R_eff [m].
    mu : float
        Friction coefficient [-].
    S_M1 : float
        [g].
    tolerance : float
        Relative change of D_M between iterations at which it stops [-].
    max_iterations : int
        Iterations at most.

    Returns
    -------
    tuple
        (D_M [m], K_M [N/m], beta_M [-], B_M [-], T_M [s], iterations).

    Raises
    ------
    RunFailure
        Without convergence in ``max_iterations``.
    """
    owner = "fixed_point"
    weight = check_real(weight, "weight", owner, low=0.0, low_open=True)
    radius = check_real(radius, "radius", owner, low=0.0, low_open=True)
    mu = check_real(mu, "mu", owner, low=0.0, high=1.0, low_open=True)
    S_M1 = check_real(S_M1, "S_M1", owner, low=0.0, high=5.0, low_open=True)
    tolerance = check_real(tolerance, "tolerance", owner, low=0.0, high=1e-2, low_open=True)
    max_iterations = check_int(max_iterations, "max_iterations", owner, low=1)
    d = G * S_M1 * 2.0 * math.pi * math.sqrt(radius / G) / (4.0 * math.pi**2)  # pendulum, B = 1
    for iteration in range(1, max_iterations + 1):
        k = weight / radius + mu * weight / d
        beta = 2.0 * mu / (math.pi * (mu + d / radius))
        b = damping_coefficient(beta)
        t = 2.0 * math.pi * math.sqrt(weight / (k * G))
        new = G * S_M1 * t / (4.0 * math.pi**2 * b)
        if abs(new - d) <= tolerance * new:
            d = new
            k = weight / radius + mu * weight / d
            beta = 2.0 * mu / (math.pi * (mu + d / radius))
            b = damping_coefficient(beta)
            t = 2.0 * math.pi * math.sqrt(weight / (k * G))
            return d, k, beta, b, t, iteration
        d = new
    raise RunFailure(f"{owner}: D_M did not converge in {max_iterations} iterations (mu = "
                     f"{mu:g}, R_eff = {radius:g} m, S_M1 = {S_M1:g} g; last D_M = {d:g} m).")


@dataclass(frozen=True)
class DirectionELF:
    """The ELF quantities of one direction of loading (x or y) at one bound.

    Attributes
    ----------
    direction : str
        ``"x"`` or ``"y"``.
    D_TM, torsion_ratio, D_TM_over_D_M : float
        Total maximum displacement [m]; 1 + y 12 e / (P_T^2 (b^2 + d^2)) of Eq. 17.5-3 [-] (NaN
        for a building without a plan) and D_TM / D_M after the 1.15 floor [-].
    floor_governs : bool
        The floor 1.15 D_M governs D_TM.
    y, e, P_T, b, d : float
        Eq. 17.5-3/4: distance of the corner bearing from the isolation system's centre of
        rigidity perpendicular to the force [m], actual plus accidental eccentricity [m], the
        period ratio [-] (at most 1), shortest and longest plan dimensions [m] (NaN without a
        plan).
    T_fb, k : float
        Fixed-base period of the superstructure in this direction [s], exponent k [-].
    heights, storey_heights : ndarray, shape (n,)
        Height of each floor above the base level and each storey's height [m].
    F : ndarray, shape (n,)
        Lateral force at each floor above the base level, F_x = C_vx V_s [N].
    storey_shear, drift, drift_ratio : ndarray, shape (n,)
        Storey shear from the forces F [N], the storey drift C_d delta_xe / I_e with C_d = R_I
        [m] and the drift ratio drift / h_sx [-].
    drift_limit : float
        0.015 [-] (17.5.6).
    """

    direction: str
    D_TM: float
    torsion_ratio: float
    D_TM_over_D_M: float
    floor_governs: bool
    y: float
    e: float
    P_T: float
    b: float
    d: float
    T_fb: float
    k: float
    heights: np.ndarray
    storey_heights: np.ndarray
    F: np.ndarray
    storey_shear: np.ndarray
    drift: np.ndarray
    drift_ratio: np.ndarray
    drift_limit: float = limit("drift_elf")

    @property
    def max_drift_ratio(self) -> float:
        """The largest storey drift ratio [-]."""
        return float(np.max(self.drift_ratio))

    @property
    def drift_passes(self) -> bool:
        """Every storey within the drift limit of 17.5.6."""
        return self.max_drift_ratio <= self.drift_limit


@dataclass(frozen=True)
class ELFBound:
    """The ELF at one bound of the properties.

    Attributes
    ----------
    bound : str
        ``"upper"`` or ``"lower"``.
    lambda_, mu : float
        Property modification factor and the friction coefficient it gives [-].
    iterations : int
        Fixed-point iterations to D_M.
    K_M, beta_M, B_M, T_M, D_M : float
        [N/m], [-], [-], [s], [m].
    V_b, V_st, V_s_formula : float
        Base shear below the isolation interface, unreduced shear above it and V_st / R_I [N].
    V_s_fixed_base, V_s_activation, V_s_wind : float
        Lower limits of V_s of 17.5.4.3 [N]: the Chapter 12 force of the fixed-base
        superstructure at T_M, V_st with V_b = 1.5 mu W, the wind base shear given (NaN: not
        given).
    V_s : float
        Design shear above the isolation interface, the largest of the four [N].
    V_s_governs : str
        Which governs: ``"formula"``, ``"fixed_base"``, ``"activation"`` or ``"wind"``.
    F_1 : float
        Force at the base level, (V_b - V_st) / R_I [N]; negative where V_st > V_b, i.e. where
        the exponent of V_st is negative (beta_M above 1/3.5 or 1/2.5), which is outside the
        ELF's conditions of 17.4.1 (the result's notes say so).
    directions : dict of str to DirectionELF
        Per direction of loading.
    """

    bound: str
    lambda_: float
    mu: float
    iterations: int
    K_M: float
    beta_M: float
    B_M: float
    T_M: float
    D_M: float
    V_b: float
    V_st: float
    V_s_formula: float
    V_s_fixed_base: float
    V_s_activation: float
    V_s_wind: float
    V_s: float
    V_s_governs: str
    F_1: float
    directions: dict[str, DirectionELF]


def _value(key: str, value: Any) -> dict[str, Any]:
    if isinstance(value, np.ndarray):
        value = [float(v) for v in value]
    elif isinstance(value, float | np.floating):
        value = None if math.isnan(value) else float(value)
    return {"value": value, "unit": UNITS.get(key, "-")}


@dataclass(frozen=True)
class ELFResult:
    """The ELF procedure at both bounds and their envelope.

    Attributes
    ----------
    name : str
        The building's name.
    site : Site
    R, R_I, I_e : float
        [-].
    W, W_s : float
        Weight on the isolators and above the base level [N].
    model : str
        Friction model whose nominal mu was used.
    mu_nominal : float
        [-].
    lambda_ : PropertyModification
    bounds : dict of str to ELFBound
        ``"upper"`` and ``"lower"``.
    notes : list of str
        What the procedure assumed or could not check.
    """

    name: str
    site: Site
    R: float
    R_I: float
    I_e: float
    W: float
    W_s: float
    model: str
    mu_nominal: float
    lambda_: PropertyModification
    bounds: dict[str, ELFBound]
    notes: list[str] = field(default_factory=list)

    @property
    def upper(self) -> ELFBound:
        """The upper bound's ELF."""
        return self.bounds["upper"]

    @property
    def lower(self) -> ELFBound:
        """The lower bound's ELF."""
        return self.bounds["lower"]

    def governing(self, key: str, direction: str | None = None) -> tuple[float, str]:
        """The largest value of ``key`` over the bounds and the bound that gives it: a field of
        :class:`ELFBound` (``"D_M"``, ``"V_s"``, ...) or, with ``direction``, of
        :class:`DirectionELF` (``"D_TM"``, ``"max_drift_ratio"``)."""
        values = {}
        for bound, result in self.bounds.items():
            source = result if direction is None else result.directions[direction]
            values[bound] = float(getattr(source, key))
        bound = max(values, key=values.get)
        return values[bound], bound

    @property
    def directions(self) -> tuple[str, ...]:
        """The directions of loading: ``("x",)`` or ``("x", "y")``."""
        return tuple(self.upper.directions)

    def to_dict(self) -> dict[str, Any]:
        """Every number keyed, each as ``{"value": ..., "unit": ...}`` (NaN as None), for JSON."""
        out: dict[str, Any] = {
            "name": self.name, "model": self.model,
            "site": {k: _value(k, getattr(self.site, k)) for k in ("S_MS", "S_M1", "T_L")},
            **{k: _value(k, getattr(self, k)) for k in ("R", "R_I", "I_e", "W", "W_s",
                                                        "mu_nominal")},
            "lambda": self.lambda_.to_dict(), "bounds": {}, "governing": {},
            "notes": list(self.notes), "clauses": dict(CLAUSES),
        }
        for bound, result in self.bounds.items():
            entry = {k: _value(k, getattr(result, k)) for k in (
                "mu", "iterations", "K_M", "beta_M", "B_M", "T_M", "D_M", "V_b", "V_st",
                "V_s_formula", "V_s_fixed_base", "V_s_activation", "V_s_wind", "V_s", "F_1")}
            entry["lambda"] = _value("lambda", result.lambda_)
            entry["V_s_governs"] = result.V_s_governs
            entry["directions"] = {
                name: {**{k: _value(k, getattr(d, k)) for k in (
                    "D_TM", "torsion_ratio", "D_TM_over_D_M", "y", "e", "P_T", "b", "d", "T_fb",
                    "k", "heights", "storey_heights", "F", "storey_shear", "drift",
                    "drift_ratio", "drift_limit", "max_drift_ratio")},
                       "floor_governs": d.floor_governs, "drift_passes": d.drift_passes}
                for name, d in result.directions.items()}
            out["bounds"][bound] = entry
        for key in ("D_M", "T_M", "V_b", "V_s"):
            value, bound = self.governing(key)
            out["governing"][key] = {**_value(key, value), "bound": bound}
        for direction in self.directions:
            for key in ("D_TM", "max_drift_ratio"):
                value, bound = self.governing(key, direction)
                out["governing"][f"{key}_{direction}"] = {**_value(key, value), "bound": bound}
        return out

    def table(self) -> str:
        """The results as a text table: quantity, unit, upper, lower, clause."""
        up, low = self.upper, self.lower
        rows = [f"ELF (ASCE/SEI 7-16 17.5): {self.name}; S_MS = {self.site.S_MS:g} g, "
                f"S_M1 = {self.site.S_M1:g} g, R = {self.R:g}, R_I = {self.R_I:g}, "
                f"{self.model} model, mu nominal = {self.mu_nominal:.4g}",
                f"{'quantity':<16} {'unit':<5} {'upper':>12} {'lower':>12}  clause"]

        def row(label: str, key: str, a: float, b: float, scale: float = 1.0,
                unit: str | None = None) -> None:
            rows.append(f"{label:<16} {unit or UNITS.get(key, '-'):<5} {a * scale:>12.5g} "
                        f"{b * scale:>12.5g}  {CLAUSES.get(key, '')}")

        row("lambda", "lambda", up.lambda_, low.lambda_)
        row("mu", "mu", up.mu, low.mu)
        for key in ("K_M", "beta_M", "B_M", "T_M", "D_M"):
            row(key, key, getattr(up, key), getattr(low, key))
        for direction in self.directions:
            row(f"D_TM ({direction})", "D_TM", up.directions[direction].D_TM,
                low.directions[direction].D_TM)
        for key in ("V_b", "V_st", "V_s_formula", "V_s_fixed_base", "V_s_activation", "V_s",
                    "F_1"):
            row(key, key, getattr(up, key), getattr(low, key), 1e-3, "kN")
        for direction in self.directions:
            row(f"drift max ({direction})", "drift",
                up.directions[direction].max_drift_ratio,
                low.directions[direction].max_drift_ratio, unit="-")
        rows.append(f"V_s governed by: upper {up.V_s_governs}, lower {low.V_s_governs}; "
                    f"drift limit {limit('drift_elf'):g} h_sx (17.5.6)")
        rows.extend(f"note: {note}" for note in self.notes)
        return "\n".join(rows)


def _fixed_base_shear(site: Site, T_M: float, W_s: float, r: float, I_e: float) -> float:
    """The Chapter 12 base shear C_s W_s of the fixed-base superstructure at T_M (12.8.1.1),
    divided by ``r`` (R_I or R: 17.5.4.3 item 1, not verified). The minimum 0.5 S_1 / (R / I_e)
    of Eq. 12.8-6 for S_1 >= 0.6 g is left out (S_1 is not an input)."""
    ratio = r / I_e
    if site.T_L is None or T_M <= site.T_L:
        cs = site.S_D1 / (T_M * ratio)
    else:
        cs = site.S_D1 * site.T_L / (T_M**2 * ratio)
    cs = min(cs, site.S_DS / ratio)
    cs = max(cs, limit("fixed_base_Cs_min") * site.S_DS * I_e, limit("fixed_base_Cs_floor"))
    return cs * W_s


def _storey_heights(config: BuildingConfig, storey_heights: object) -> np.ndarray:
    n = config.building.n_storeys
    given = storey_heights
    if given is None and config.plan is not None and config.plan.storey_heights is not None:
        given = config.plan.storey_heights
    if given is None:
        raise InputError(f"The 'storey_heights' parameter of {_OWNER} must be given (one height "
                         "[m] for all storeys or one per storey) for a building file without "
                         "[plan] storey_heights: the vertical distribution and the drift need "
                         "them. Got None instead.")
    heights = check_array(np.atleast_1d(np.asarray(given, dtype=float)), "storey_heights",
                          _OWNER, low=0.0, low_open=True)
    if heights.size == 1:
        heights = np.full(n, float(heights[0]))
    if heights.shape != (n,):
        raise InputError(f"The 'storey_heights' parameter of {_OWNER} must have one value or one "
                         f"per storey ({n}). Got {heights.size} instead.")
    return heights


def _torsion(config: BuildingConfig, direction: str) -> tuple[float, ...]:
    """(ratio, y, e, P_T, b, d) of Eq. 17.5-3/4 for loading along ``direction``; NaN without a
    plan."""
    plan = config.plan
    if plan is None:
        nan = float("nan")
        return nan, nan, nan, nan, nan, nan
    if plan.dimensions is None:
        raise InputError(f"The 'dimensions' of the [plan] must be given for {_OWNER}: b and d "
                         "of Eq. 17.5-3 and the radius of gyration of Eq. 17.5-4. Got None "
                         "instead.")
    a_x, a_y = (float(v) for v in plan.dimensions)
    b, d = min(a_x, a_y), max(a_x, a_y)
    building = config.building
    bearings = np.asarray(building.bearing_positions, dtype=float)
    rigidity = bearings.mean(axis=0)  # identical bearings: the centroid
    masses = building.level_masses
    centre = masses @ np.asarray(building.level_centres) / masses.sum()
    relative = bearings - rigidity
    actual = centre - rigidity
    accidental = limit("accidental_eccentricity")
    if direction == "x":  # force along x: distances and eccentricity along y
        y = float(np.max(np.abs(relative[:, 1])))
        e = abs(float(actual[1])) + accidental * a_y
    else:
        y = float(np.max(np.abs(relative[:, 0])))
        e = abs(float(actual[0])) + accidental * a_x
    r_i = math.sqrt((b * b + d * d) / 12.0)
    p_t = math.sqrt(float(np.mean(np.sum(relative**2, axis=1)))) / r_i
    p_t = min(p_t, limit("P_T_max"))
    ratio = 1.0 + y / p_t**2 * 12.0 * e / (b * b + d * d)
    return ratio, y, e, p_t, b, d


def _direction(config: BuildingConfig, direction: str, D_M: float, beta_M: float, V_s: float,
               R_I: float, I_e: float, heights: np.ndarray) -> DirectionELF:
    building = config.building
    column = 0 if direction == "x" else 1
    stiffness = np.asarray(building.storey_table)[:, column]
    T_fb = float(modal_analysis(np.diag(building.floor_masses),
                                shear_stiffness_matrix(stiffness)).periods[0])
    ratio, y, e, p_t, b, d = _torsion(config, direction)
    floor = limit("D_TM_over_D_M_min")
    over = floor if math.isnan(ratio) else max(ratio, floor)
    k = limit("k_factor") * beta_M * T_fb
    levels = np.cumsum(heights)
    weights = building.floor_masses * G
    shares = weights * levels**k / np.sum(weights * levels**k)
    forces = shares * V_s
    shear = np.cumsum(forces[::-1])[::-1]
    drift = R_I * shear / stiffness / I_e  # 12.8.6 with C_d = R_I (17.5.6)
    return DirectionELF(direction, over * D_M, ratio, over, math.isnan(ratio) or ratio < floor,
                        y, e, p_t, b, d, T_fb, k, levels, heights, forces, shear, drift,
                        drift / heights)


def elf(config: BuildingConfig, site: Site | tuple[float, ...], lambda_: PropertyModification,
        *, R: float, I_e: float = 1.0, model: str | None = None, mu: float | None = None,
        storey_heights: float | list[float] | None = None, wind_base_shear: float | None = None,
        abrupt_transition: bool = True, fixed_base_r: str = "R_I",
        tolerance: float = 1e-12) -> ELFResult:
    """The equivalent lateral force procedure (Sec. 17.5) at the upper and lower bound.

    Parameters
    ----------
    config : BuildingConfig
        The building file (:func:`structures.config.load_config`): masses, storey stiffnesses,
        the bearings' R_eff and friction, the plan's bearings, dimensions and eccentricity.
    site : Site or (S_MS, S_M1[, T_L])
        MCE_R parameters [g, g, s].
    lambda_ : PropertyModification
        lambda_max and lambda_min.
    R : float
        Response modification coefficient of the superstructure's system [-] (R_I = 3/8 R in
        [1, 2]).
    I_e : float
        Importance factor [-], in [1, 1.5].
    model : str or None
        The friction model whose nominal mu is used (:func:`nominal_mu`; default the file's).
    mu : float or None
        The nominal friction coefficient [-], in place of the model's.
    storey_heights : float, list of float or None
        Storey heights [m] (default the plan's ``storey_heights``).
    wind_base_shear : float or None
        Wind base shear above the isolation interface [N] (17.5.4.3 item 2), if known.
    abrupt_transition : bool
        The isolation system passes abruptly from pre-slip to sliding (a friction pendulum):
        V_st with the exponent (1 - 3.5 beta_M) of 17.5.4.2 instead of (1 - 2.5 beta_M)
        (``LIMITS["V_st_exponent_factor_abrupt"]``).
    fixed_base_r : {"R_I", "R"}
        The coefficient that divides the Chapter 12 force of the fixed-base limit of 17.5.4.3
        item 1 (which the text means was not verified; ``"R"`` is the larger, less binding).
    tolerance : float
        Relative tolerance of the fixed point of D_M [-].

    Returns
    -------
    ELFResult

    Raises
    ------
    InputError
        A bad argument (named): a site value out of range, lambda not a PropertyModification,
        mu out of (0, 1], a missing storey height, a plan without dimensions; or mu times lambda
        outside (0, 1].

    Warns
    -----
    InputWarning
        lambda outside the limits of 17.2.8.4 as read (:meth:`PropertyModification.limit_notes`).
    """
    check_instance(config, "config", _OWNER, BuildingConfig, "a BuildingConfig")
    if not isinstance(site, Site):
        if not isinstance(site, tuple | list) or len(site) not in (2, 3):
            raise InputError(f"The 'site' parameter of {_OWNER} must be a Site or (S_MS, S_M1[, "
                             f"T_L]). Got {site!r} instead.")
        site = Site(*site)
    check_instance(lambda_, "lambda_", _OWNER, PropertyModification, "a PropertyModification")
    R_I = response_modification(R)
    I_e = check_real(I_e, "I_e", _OWNER, low=1.0, high=1.5)
    if model is not None:
        model = str(model)
        if model not in MODELS:
            raise InputError(f"The 'model' parameter of {_OWNER} must be one of {MODELS}. Got "
                             f"{model!r} instead.")
    model = model or config.friction["model"]
    mu_nominal = (nominal_mu(config, model) if mu is None
                  else check_real(mu, "mu", _OWNER, low=0.0, high=1.0, low_open=True))
    wind = (float("nan") if wind_base_shear is None
            else check_real(wind_base_shear, "wind_base_shear", _OWNER, low=0.0))
    heights = _storey_heights(config, storey_heights)
    if not isinstance(abrupt_transition, bool):
        raise InputError(f"The 'abrupt_transition' parameter of {_OWNER} must be True or False. "
                         f"Got {abrupt_transition!r} instead.")
    fixed_base_r = check_choice(fixed_base_r, "fixed_base_r", _OWNER, ("R_I", "R"))
    exponent_key = ("V_st_exponent_factor_abrupt" if abrupt_transition
                    else "V_st_exponent_factor")
    notes = lambda_.limit_notes()
    for note in notes:
        warnings.warn(InputWarning(note), stacklevel=2)
    building = config.building
    W = building.weight
    W_s = float(building.floor_masses.sum()) * G
    radius = float(config.bearing_geometry["effective_radius"])
    directions = building.directions
    bounds = {}
    for bound in BOUNDS:
        factor = lambda_.factor(bound)
        mu_b = mu_nominal * factor
        if not 0.0 < mu_b <= 1.0:
            raise InputError(f"The 'lambda_' parameter of {_OWNER} must keep mu in (0, 1]: "
                             f"{factor:g} x {mu_nominal:g} = {mu_b:g} ({bound} bound).")
        D_M, K_M, beta_M, B_M, T_M, iterations = fixed_point(W, radius, mu_b, site.S_M1,
                                                             tolerance=tolerance)
        V_b = K_M * D_M
        exponent = 1.0 - limit(exponent_key) * beta_M
        V_st = V_b * (W_s / W) ** exponent
        candidates = {
            "formula": V_st / R_I,
            "fixed_base": _fixed_base_shear(site, T_M, W_s,
                                            R_I if fixed_base_r == "R_I" else float(R), I_e),
            "activation": limit("activation_factor") * mu_b * W * (W_s / W) ** exponent,
            "wind": wind,
        }
        governs = max((k for k in candidates if not math.isnan(candidates[k])),
                      key=candidates.get)
        V_s = candidates[governs]
        per_direction = {d: _direction(config, d, D_M, beta_M, V_s, R_I, I_e, heights)
                         for d in directions}
        bounds[bound] = ELFBound(bound, factor, mu_b, iterations, K_M, beta_M, B_M, T_M, D_M,
                                 V_b, V_st, candidates["formula"], candidates["fixed_base"],
                                 candidates["activation"], wind, V_s, governs,
                                 (V_b - V_st) / R_I, per_direction)
    notes = [*notes,
             "bearings rigid-plastic (yield displacement neglected) in K_M and beta_M",
             f"fixed-base limit of 17.5.4.3 item 1 divided by {fixed_base_r} (which one was not "
             "verified); "
             f"activation limit ({LIMITS['activation_factor'].clause}) as 1.5 mu W, undivided",
             "wind base shear not given" if wind_base_shear is None else "wind base shear given",
             f"V_st with the exponent (1 - {limit(exponent_key):g} beta_M) "
             f"({'abrupt' if abrupt_transition else 'smooth'} transition to sliding, 17.5.4.2)"]
    for result in bounds.values():
        beta_m, t_m = result.beta_M, result.T_M
        if beta_m > limit("elf_beta_M_max") or t_m > limit("elf_T_M_max"):
            notes.append(
                f"{LIMITS['elf_beta_M_max'].clause}: the ELF procedure is permitted with beta_M "
                f"<= {limit('elf_beta_M_max'):.0%} and T_M <= {limit('elf_T_M_max'):g} s (as "
                f"read); the {result.bound} bound has beta_M = {result.beta_M:.1%}, T_M = "
                f"{result.T_M:.3g} s: a response history analysis is required")
    if config.plan is None:
        notes.append("no plan: D_TM is the floor 1.15 D_M of 17.5.3.3 (torsion not computed)")
    return ELFResult(config.name, site, float(R), R_I, I_e, W, W_s, model, mu_nominal, lambda_,
                     bounds, notes)
