"""The ELF procedure of ASCE/SEI 7-16 Sec. 17.5 (structures.design.elf) against hand
calculations written out here, for the two example buildings: the friction pendulum's K_M and
beta_M at D_M in closed form, B_M from Table 17.5-1, the fixed point of D_M found by another
method (bisection on the residual), D_TM with the plan's torsion and its 1.15 floor, V_b, V_st,
V_s and its limits, the vertical distribution and the drifts."""

from __future__ import annotations

import itertools
import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from structures.config import load_config
from structures.design import PropertyModification, Site, damping_coefficient, elf
from structures.design.elf import fixed_point, nominal_mu, response_modification

ROOT = Path(__file__).resolve().parents[2]
g = 9.80665

# Table 17.5-1, written out again for the hand calculation
TABLE = [(0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9),
         (0.50, 2.0)]


def hand_B(beta: float) -> float:
    """Linear interpolation in TABLE, held at the ends."""
    if beta <= TABLE[0][0]:
        return TABLE[0][1]
    for (b0, v0), (b1, v1) in itertools.pairwise(TABLE):
        if beta <= b1:
            return v0 + (v1 - v0) * (beta - b0) / (b1 - b0)
    return TABLE[-1][1]


def hand_D_M(mu: float, R: float, S_M1: float) -> float:
    """D_M as the root of D - g S_M1 T(D) / (4 pi^2 B(beta(D))) by bisection (W cancels)."""
    def residual(D: float) -> float:
        beta = 2 * mu / (math.pi * (mu + D / R))
        T = 2 * math.pi / math.sqrt(g * (1 / R + mu / D))
        return D - g * S_M1 * T / (4 * math.pi**2 * hand_B(beta))
    return brentq(residual, 1e-4, 5.0, xtol=1e-14, rtol=1e-14)


@pytest.fixture(scope="module")
def planar():
    return load_config(ROOT / "examples" / "five_storey.toml")


@pytest.fixture(scope="module")
def plan():
    return load_config(ROOT / "examples" / "five_storey_plan.toml")


@pytest.mark.parametrize("beta, expected", [
    (0.02, 0.8), (0.05, 1.0), (0.10, 1.2), (0.20, 1.5), (0.30, 1.7), (0.40, 1.9), (0.50, 2.0),
    (0.0, 0.8), (0.01, 0.8), (0.035, 0.9), (0.15, 1.35), (0.25, 1.6), (0.45, 1.95),
    (0.6, 2.0)])
def test_B_M_from_table_17_5_1(beta, expected):
    assert damping_coefficient(beta) == pytest.approx(expected, abs=1e-12)


def test_R_I_is_three_eighths_R_within_1_and_2():
    assert response_modification(4.0) == 1.5
    assert response_modification(2.0) == 1.0  # 0.75 raised to 1
    assert response_modification(8.0) == 2.0  # 3 lowered to 2


def test_fixed_point_is_the_root_and_closed_forms_hold():
    W, R, mu, S_M1 = 1.0e7, 3.0, 0.06, 0.9
    D, K, beta, B, T, iterations = fixed_point(W, R, mu, S_M1)
    assert pytest.approx(hand_D_M(mu, R, S_M1), rel=1e-10) == D
    assert pytest.approx(W / R + mu * W / D, rel=1e-14) == K
    assert beta == pytest.approx(2 * mu / (math.pi * (mu + D / R)), rel=1e-14)
    # beta_M as EDC / (2 pi K D^2) of the rigid-plastic loop, EDC = 4 mu W D
    assert beta == pytest.approx(4 * mu * W * D / (2 * math.pi * K * D**2), rel=1e-12)
    assert pytest.approx(2 * math.pi * math.sqrt(W / (K * g)), rel=1e-14) == T
    assert pytest.approx(g * S_M1 * T / (4 * math.pi**2 * B), rel=1e-11) == D
    assert 1 < iterations < 100


def test_planar_building_against_the_hand_calculation(planar):
    """five_storey.toml, mu = 0.05 nominal, lambda 1.8 / 0.6, S_MS 1.5 g, S_M1 0.6 g, T_L 8 s,
    R = 4 (R_I = 1.5), storeys 3.5 m, the smooth transition's exponent (1 - 2.5 beta_M)."""
    lam = PropertyModification.overall(1.8, 0.6)
    result = elf(planar, Site(1.5, 0.6, 8.0), lam, R=4.0, mu=0.05, storey_heights=3.5,
                 abrupt_transition=False)
    W = (500e3 + 5 * 400e3) * g  # 24 516 625 N
    W_s = 5 * 400e3 * g
    R, R_I = 4.5, 1.5
    k_storey = planar.building.storey_stiffnesses  # the file's: fixed-base period 0.5 s
    assert pytest.approx(W) == result.W and result.W_s == pytest.approx(W_s)
    assert result.R_I == R_I
    for bound, mu in (("upper", 0.09), ("lower", 0.03)):
        r = result.bounds[bound]
        D = hand_D_M(mu, R, 0.6)
        K = W / R + mu * W / D
        beta = 2 * mu / (math.pi * (mu + D / R))
        T = 2 * math.pi * math.sqrt(W / (K * g))
        assert r.mu == pytest.approx(mu, rel=1e-14)
        assert pytest.approx(D, rel=1e-10) == r.D_M
        assert pytest.approx(K, rel=1e-9) == r.K_M
        assert r.beta_M == pytest.approx(beta, rel=1e-9)
        assert pytest.approx(hand_B(beta), rel=1e-9) == r.B_M
        assert pytest.approx(T, rel=1e-9) == r.T_M
        V_b = K * D
        V_st = V_b * (W_s / W) ** (1 - 2.5 * beta)
        S_DS, S_D1 = 1.0, 0.4
        Cs = max(min(S_D1 / (T * R_I), S_DS / R_I), 0.044 * S_DS, 0.01)
        limits = {"formula": V_st / R_I, "fixed_base": Cs * W_s,
                  "activation": 1.5 * mu * W * (W_s / W) ** (1 - 2.5 * beta)}
        V_s = max(limits.values())
        assert r.V_b == pytest.approx(V_b, rel=1e-9)
        assert r.V_st == pytest.approx(V_st, rel=1e-9)
        assert r.V_s_fixed_base == pytest.approx(limits["fixed_base"], rel=1e-9)
        assert r.V_s_activation == pytest.approx(limits["activation"], rel=1e-9)
        assert r.V_s == pytest.approx(V_s, rel=1e-9)
        assert r.V_s_governs == max(limits, key=limits.get)
        assert pytest.approx((V_b - V_st) / R_I, rel=1e-9) == r.F_1
        x = r.directions["x"]
        assert pytest.approx(1.15 * D, rel=1e-10) == x.D_TM and x.floor_governs
        assert x.T_fb == pytest.approx(0.5, rel=1e-9)
        k = 14 * beta * 0.5
        h = 3.5 * np.arange(1, 6)
        w = 400e3 * g * np.ones(5)
        F = w * h**k / np.sum(w * h**k) * V_s
        shear = np.array([F[i:].sum() for i in range(5)])
        drift = R_I * shear / k_storey
        assert x.k == pytest.approx(k, rel=1e-9)
        np.testing.assert_allclose(x.F, F, rtol=1e-9)
        np.testing.assert_allclose(x.storey_shear, shear, rtol=1e-9)
        np.testing.assert_allclose(x.drift_ratio, drift / 3.5, rtol=1e-9)
        assert x.drift_passes == bool(np.all(drift / 3.5 <= 0.015))
    assert result.governing("D_M") == (result.lower.D_M, "lower")
    assert result.governing("V_b")[1] in ("upper", "lower")


def test_plan_building_against_the_hand_calculation(plan):
    """five_storey_plan.toml, the constant model's mu, lambda from its parts, S_MS 1.2 g,
    S_M1 0.5 g, R = 3 (R_I = 1.125), the abrupt transition's exponent (1 - 3.5 beta_M)."""
    lam = PropertyModification(ae_max=1.2, test_max=1.4, spec_max=1.15,
                               ae_min=1.0, test_min=0.7, spec_min=0.85)
    lam_max = (1 + 0.75 * (1.2 - 1)) * 1.4 * 1.15  # 1.8515
    lam_min = (1 - 0.75 * (1 - 1.0)) * 0.7 * 0.85  # 0.595
    mu0 = plan.bearing("constant").friction.mu
    assert nominal_mu(plan, "constant") == mu0
    result = elf(plan, (1.2, 0.5), lam, R=3.0, model="constant")
    assert pytest.approx(1.125) == result.R_I
    assert result.upper.mu == pytest.approx(lam_max * mu0, rel=1e-14)
    assert result.lower.mu == pytest.approx(lam_min * mu0, rel=1e-14)
    # Torsion: bearings at x = -10, 0, 10 and y = -5, 5 (centroid 0); plan 24 m x 12 m;
    # centre of mass: floors (2000 t) at (1.2, 0.6), base (500 t) at 0 -> (0.96, 0.48)
    r_I = math.sqrt((12**2 + 24**2) / 12)  # sqrt(60)
    P_T = min(math.sqrt((4 * 100 + 6 * 25) / 6) / r_I, 1.0)  # 1.236 -> 1
    ratio_x = 1 + 5 / P_T**2 * 12 * (0.48 + 0.05 * 12) / (12**2 + 24**2)  # 1.09
    ratio_y = 1 + 10 / P_T**2 * 12 * (0.96 + 0.05 * 24) / (12**2 + 24**2)  # 1.36
    assert ratio_x == pytest.approx(1.09) and ratio_y == pytest.approx(1.36)
    for bound in ("upper", "lower"):
        r = result.bounds[bound]
        D = hand_D_M(r.mu, 4.5, 0.5)
        assert pytest.approx(D, rel=1e-10) == r.D_M
        W, W_s = 2.5e6 * 9.80665, 2.0e6 * 9.80665
        beta = 2 * r.mu / (math.pi * (r.mu + D / 4.5))
        V_b = (W / 4.5 + r.mu * W / D) * D
        V_st = V_b * (W_s / W) ** (1 - 3.5 * beta)
        v_b, v_st = r.V_b, r.V_st
        assert v_b == pytest.approx(V_b, rel=1e-9)
        assert v_st == pytest.approx(V_st, rel=1e-9)
        x, y = r.directions["x"], r.directions["y"]
        assert x.P_T == 1.0 and x.e == pytest.approx(1.08) and x.y == 5.0
        assert x.torsion_ratio == pytest.approx(ratio_x, rel=1e-12)
        assert pytest.approx(1.15 * D, rel=1e-10) == x.D_TM and x.floor_governs
        assert y.torsion_ratio == pytest.approx(ratio_y, rel=1e-12)
        assert pytest.approx(1.36 * D, rel=1e-10) == y.D_TM and not y.floor_governs
    assert result.governing("D_TM", "y") == (result.lower.directions["y"].D_TM, "lower")


def test_result_converts_to_json_with_units(plan):
    result = elf(plan, Site(1.5, 0.6), PropertyModification.overall(1.8, 0.6), R=2.0)
    data = json.loads(json.dumps(result.to_dict()))
    assert data["bounds"]["lower"]["D_M"]["unit"] == "m"
    assert data["bounds"]["upper"]["V_s"]["unit"] == "N"
    assert data["bounds"]["upper"]["directions"]["y"]["F"]["unit"] == "N"
    assert data["governing"]["D_TM_y"]["bound"] == "lower"
    assert data["site"]["T_L"]["value"] is None
    text = result.table()
    assert "D_TM (y)" in text and "Table 17.5-1" in text


@pytest.mark.parametrize("fixed_base_r, T_L", [("R", None), ("R_I", 2.0), ("R", 2.0)])
def test_fixed_base_limit_of_17_5_4_3(planar, fixed_base_r, T_L):
    """C_s of 12.8.1.1 at T_M: S_D1 / (T R'), T_L S_D1 / (T^2 R') past T_L, at most S_DS / R',
    at least 0.044 S_DS and 0.01, with R' = R = 4 or R_I = 1.5."""
    result = elf(planar, Site(1.5, 0.6, T_L), PropertyModification.overall(1.8, 0.6), R=4.0,
                 mu=0.05, storey_heights=3.5, fixed_base_r=fixed_base_r)
    r_prime = 4.0 if fixed_base_r == "R" else 1.5
    W_s = 2.0e6 * g
    for bound in ("upper", "lower"):
        T = result.bounds[bound].T_M
        cs = 0.4 / (T * r_prime) if T_L is None or T <= T_L else 0.4 * T_L / (T**2 * r_prime)
        cs = max(min(cs, 1.0 / r_prime), 0.044 * 1.0, 0.01)
        v_fixed = result.bounds[bound].V_s_fixed_base
        assert v_fixed == pytest.approx(cs * W_s, rel=1e-12)


def test_elf_says_where_17_4_1_does_not_permit_it(planar):
    result = elf(planar, Site(1.5, 0.6), PropertyModification.overall(1.8, 0.6), R=4.0,
                 mu=0.05, storey_heights=3.5)
    assert result.upper.beta_M > 0.30 > result.lower.beta_M
    notes = [n for n in result.notes if n.startswith("17.4.1")]
    assert len(notes) == 1 and "upper bound" in notes[0]
