"""The numeric limits of ASCE/SEI 7-16 Chapter 17 the design layer uses, in one table, each with
its clause and equation, so that a reader can check them against the text of the standard.

What was verified and what not
------------------------------
The standard's text is copyrighted and was not at hand: the searches of public pages (corpus
``pages`` and ``docs``) for Sec. 17.2.8.4, Table 17.5-1, Eq. 17.5-3 and Sec. 17.6 returned no
passage of Chapter 17. Every value below is therefore written from the engineering literature on
ASCE 7-16 Chapter 17 as the author knows it, and each entry's ``verified`` says so (False for
all): a value on which that knowledge is firm has a plain note, one in doubt says what is in doubt
(a percentage, an equation number, whether a bound is a floor or a check). Check them against the
text before relying on a design; change them here, in one place.

One public, non-authoritative cross-check was found (corpus ``code``): an MIT-licensed ASCE 7-16
equivalent-static script for isolated structures by Amin Moghaddasi on GitHub. It agrees with
this table on Table 17.5-1's points, R_I = 3/8 R in [1, 2], F_1 = (V_b - V_st) / R_I,
k = 14 beta_M T_fb and Eq. 17.5-4 for P_T, and it has the exponent (1 - 3.5 beta_M) for systems
with an abrupt transition (``V_st_exponent_factor_abrupt``). It divides the activation limit of
17.5.4.3 by R_I, where this module does not (``activation_factor``): one of the two readings is
wrong, and which was not settled.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from dcfpb.common.validation import check_real

__all__ = ["LIMITS", "Limit", "damping_coefficient", "limit", "limits_table"]


@dataclass(frozen=True)
class Limit:
    """One numeric limit of the standard.

    Attributes
    ----------
    key : str
        The name the code looks it up by.
    value : float
        The number [unit].
    unit : str
        Its unit ("-" for a ratio).
    clause : str
        Section (and equation or table) of ASCE/SEI 7-16.
    meaning : str
        What it limits, in words.
    verified : bool
        Whether the value was checked against the text of the standard in this package.
    note : str
        Doubts: what was not verified, alternatives read elsewhere.
    """

    key: str
    value: float
    unit: str
    clause: str
    meaning: str
    verified: bool = False
    note: str = ""

    def to_dict(self) -> dict[str, object]:
        """The entry as a plain dict (for JSON)."""
        return asdict(self)


_L = Limit
LIMITS: dict[str, Limit] = {entry.key: entry for entry in (
    _L("lambda_ae_adjustment", 0.75, "-", "17.2.8.4, Eq. 17.2-1 and 17.2-2",
       "share of the aging and environmental factor's deviation from 1 that enters lambda: "
       "1 + 0.75 (lambda_ae,max - 1), 1 - 0.75 (1 - lambda_ae,min)",
       note="firm from the literature; not checked against the text here"),
    _L("lambda_max_floor", 1.8, "-", "17.2.8.4, Eq. 17.2-1 (to be checked)",
       "lambda_max as assembled is at least this",
       note="in doubt: whether 1.8 is a floor on lambda_max in Eq. 17.2-1 or a default for "
            "unqualified products (C17.2.8.4); the code warns when lambda_max is below it and "
            "does not raise it"),
    _L("lambda_min_ceiling", 0.60, "-", "17.2.8.4, Eq. 17.2-2 (to be checked)",
       "lambda_min as assembled is at most this",
       note="in doubt as lambda_max_floor; the code warns when lambda_min is above it"),
    _L("elf_beta_M_max", 0.30, "-", "17.4.1 (to be checked)",
       "the ELF procedure is permitted only where beta_M at D_M is at most 30 % (among other "
       "conditions: site, period, regularity, S_1)",
       note="from the literature on the 2016 edition; the other conditions of 17.4.1 are not "
            "checked by the code"),
    _L("elf_T_M_max", 5.0, "s", "17.4.1 (to be checked)",
       "the ELF procedure is permitted only where T_M is at most 5.0 s",
       note="from the literature"),
    _L("D_TM_over_D_M_min", 1.15, "-", "17.5.3.3, Eq. 17.5-3",
       "total maximum displacement D_TM not less than 1.15 D_M",
       note="firm from the literature"),
    _L("accidental_eccentricity", 0.05, "-", "17.5.3.3 (definition of e)",
       "accidental eccentricity, a fraction of the longest plan dimension perpendicular to the "
       "force, added to the actual eccentricity",
       note="firm from the literature"),
    _L("P_T_max", 1.0, "-", "17.5.3.3, Eq. 17.5-4",
       "ratio of translational to torsional period P_T need not be taken greater than 1",
       note="firm from the literature"),
    _L("R_I_factor", 3.0 / 8.0, "-", "17.5.4.2", "R_I = 3/8 R",
       note="firm from the literature"),
    _L("R_I_max", 2.0, "-", "17.5.4.2", "R_I not greater than 2.0",
       note="firm from the literature"),
    _L("R_I_min", 1.0, "-", "17.5.4.2", "R_I not less than 1.0",
       note="firm from the literature"),
    _L("V_st_exponent_factor", 2.5, "-", "17.5.4.2, Eq. 17.5-7",
       "V_st = V_b (W_s / W)^(1 - 2.5 beta_M)",
       note="firm from the literature; the equation number may be 17.5-7 or 17.5-6"),
    _L("V_st_exponent_factor_abrupt", 3.5, "-", "17.5.4.2 (after Eq. 17.5-7)",
       "(1 - 3.5 beta_M) in place of (1 - 2.5 beta_M) for isolation systems with an abrupt "
       "transition from pre-slip to post-slip (or pre-yield to post-yield) behaviour",
       note="from the literature and a third-party ASCE 7-16 isolation script (Amin-Moghaddasi "
            "on GitHub, 'abrupt_transition'), not the text; a friction pendulum slides after "
            "a pre-slip of about 2 u_y (1 mm here), so elf() takes it by default "
            "(abrupt_transition=True)"),
    _L("activation_factor", 1.5, "-", "17.5.4.3 item 3",
       "V_s not less than V_st with V_b set to 1.5 times the break-away friction of a sliding "
       "system",
       note="in doubt: the code uses 1.5 x mu_upper W (the kinetic friction at the upper bound "
            "as the break-away level) and does not divide it by R_I"),
    _L("fixed_base_Cs_min", 0.044, "-", "12.8.1.1, Eq. 12.8-5 (via 17.5.4.3 item 1)",
       "C_s of the fixed-base limit not less than 0.044 S_DS I_e",
       note="firm from the literature; with 0.01 below (Eq. 12.8-5)"),
    _L("fixed_base_Cs_floor", 0.01, "-", "12.8.1.1, Eq. 12.8-5", "C_s not less than 0.01",
       note="firm from the literature"),
    _L("design_over_mce", 2.0 / 3.0, "-", "11.4.5", "S_DS = 2/3 S_MS, S_D1 = 2/3 S_M1",
       note="firm"),
    _L("k_factor", 14.0, "-", "17.5.5, Eq. 17.5-11 (numbering to be checked)",
       "exponent of the vertical distribution k = 14 beta_M T_fb",
       note="the brief names it Eq. 17.5-9; the literature places F_1 in 17.5-8, F_x in 17.5-9, "
            "C_vx in 17.5-10 and k in 17.5-11"),
    _L("drift_elf", 0.015, "-", "17.5.6", "storey drift of the ELF not more than 0.015 h_sx",
       note="firm; the drift is computed as in 12.8.6 with C_d = R_I"),
    _L("drift_rha", 0.020, "-", "17.6.4.4", "storey drift of the response history not more "
       "than 0.020 h_sx", note="firm from the literature"),
    _L("rha_D_TM_min", 0.80, "-", "17.6.3 / 17.6.4 (numbering to be checked)",
       "D_TM of the response history not less than 80 % of the ELF's",
       note="percentage firm from the literature, clause number in doubt"),
    _L("rha_V_b_min", 0.90, "-", "17.6.3 / 17.6.4 (numbering to be checked)",
       "V_b of the response history not less than 90 % of the ELF's",
       note="percentage firm from the literature, clause number in doubt"),
    _L("rha_V_s_min_regular", 0.80, "-", "17.6.3 / 17.6.4 (numbering to be checked)",
       "V_s of the response history not less than 80 % of the ELF's (regular superstructure)",
       note="in doubt: 80 % regular is the literature's reading of 7-16; 7-10 had 60 %/80 %"),
    _L("rha_V_s_min_irregular", 1.00, "-", "17.6.3 / 17.6.4 (numbering to be checked)",
       "V_s of the response history not less than 100 % of the ELF's (irregular "
       "superstructure)", note="in doubt as the regular case"),
    _L("min_pairs", 7, "-", "17.3.2", "at least seven pairs of ground motions",
       note="firm from the literature (7 for averaging; fewer takes the maximum); simulated "
            "pairs may make up the number where recorded ones are too few"),
    _L("rha_scaling_fraction", 1.0, "-", "17.3.3",
       "the average of the pairs' maximum-direction (RotD100) spectra not below this share of "
       "the MCE_R target over the period range",
       note="in doubt: 1.0 (the target itself) is this package's reading of 17.3.3 for "
            "isolated structures; Chapter 16 (16.2.3.2) uses 90 %, and some summaries of 7-16 "
            "give 90 % for Chapter 17 as well. A value of 0.9 here would scale the suite "
            "lower by up to 10 %"),
    _L("accidental_shift", 0.05, "-", "17.6.2.1 (as read)",
       "response history: the centre of mass of each level moved from its computed place by "
       "this share of the plan dimension along that direction, separately along x and y, "
       "each sign (four positions)",
       note="from the literature on 7-16 (and as FEMA P-1050 and commercial programs apply "
            "it); whether the bearings' gravity loads move with the mass is not said in what "
            "was read: this package holds them (the mass moves, not the weight on the "
            "bearings), with an option to let them follow"),
    _L("bearing_capacity", 1.0, "-", "17.2.4.4 / 17.2.6 (as read)",
       "isolator displacement demand over the bearing's displacement capacity at most 1",
       note="the isolation system must remain stable to D_TM; the package checks the "
            "enveloped average against the building file's displacement_capacity, and counts "
            "every run that stopped there"),
    _L("uplift", 0.0, "N", "17.2.4.7 (as read)",
       "smallest axial load of a bearing (0 or less: local uplift)",
       note="7-16 permits local uplift of individual units where shown harmless; the package "
            "reports it as a failed check for the engineer to justify"),
    _L("period_range_low", 0.75, "-", "17.3.3", "scaling period range from 0.75 T_M of the "
       "upper bound properties", note="firm from the literature"),
    _L("period_range_high", 1.25, "-", "17.3.3", "scaling period range up to 1.25 T_M of the "
       "lower bound properties", note="firm from the literature; spectra as RotD100 (maximum "
                                        "direction)"),
    _L("prototype_item4_cycles_min", 10, "-", "17.8.2.2 item 4",
       "cycles at 0.75 D_TM: 30 S_M1 / (S_MS B_M), not less than 10",
       note="as isolator.protocols.long_duration_cycles"),
)}
"""Every limit by key."""

B_M_TABLE = (
    (0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0))
"""Table 17.5-1: effective damping beta_M [-] and the damping coefficient B_M [-]; linear
interpolation between, 0.8 below 2 % and 2.0 above 50 % (firm from the literature, not checked
against the text here)."""


def limit(key: str) -> float:
    """The value of the limit ``key`` of :data:`LIMITS`."""
    return float(LIMITS[key].value)


def damping_coefficient(beta: float) -> float:
    """B_M of Table 17.5-1 for the effective damping ``beta`` [-] (a fraction, 0.2 for 20 %),
    interpolated linearly between the table's points and held at its ends."""
    beta = check_real(beta, "beta", "damping_coefficient", low=0.0)
    betas, values = zip(*B_M_TABLE, strict=True)
    return float(np.interp(beta, betas, values))


def limits_table() -> str:
    """The limits as a text table: key, value, unit, clause, meaning."""
    rows = [f"{'key':<26} {'value':>7} {'unit':<4} {'clause':<44} meaning"]
    for entry in LIMITS.values():
        rows.append(f"{entry.key:<26} {entry.value:>7.4g} {entry.unit:<4} {entry.clause:<44} "
                    f"{entry.meaning}")
    rows.append("Table 17.5-1 B_M: " + ", ".join(f"{b:g}: {v:g}" for b, v in B_M_TABLE))
    return "\n".join(rows)
