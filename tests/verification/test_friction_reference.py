"""The compiled friction kernels against Eq. 7 written plainly (isolator.friction.eq7).

The kernels solve mu = mu_t0 gamma(p) alpha(v) beta(T) with the contact temperature depending on
mu through the newest interval's flux, T = T_base + b q(mu), q = mu p |v| / surfaces. Here the
same fixed point is found by bracketing (scipy's brentq) on the plain numpy Eq. 7, and its
velocity derivative by central differences of those independent solutions; the packed layout
is checked name by name, and the readable element (PTVFrictionState) through its first trial.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from isolator.compiled import layout
from isolator.compiled.kernels import ptv_friction
from isolator.compiled.layout import PTV_PARAMETERS, pack_ptv
from isolator.factors import KumarFactors, PaperFactors
from isolator.friction import DEPENDENCIES, PTVFriction, eq7
from isolator.heating import MonitorLine

FACTORS = {0: PaperFactors(), 1: KumarFactors()}


def test_named_constants_follow_the_specification():
    for index, name in enumerate(PTV_PARAMETERS):
        assert getattr(layout, name.upper()) == index
    packed = pack_ptv({name: 10.0 + i for i, name in enumerate(PTV_PARAMETERS)})
    assert packed.tolist() == [10.0 + i for i in range(len(PTV_PARAMETERS))]
    assert pack_ptv({"mu_t0": 0.07})[layout.MU_T0] == 0.07
    with pytest.raises(KeyError, match="mu_to"):
        pack_ptv({"mu_to": 0.07})


def _fixed_point(code, dependencies, mu_t0, base, b, pressure, speed, surfaces):
    """mu = eq7(p, v, base + b mu p v / surfaces), by bracketing (no Newton, no kernels)."""
    def residual(mu):
        temperature = base + b * mu * pressure * speed / surfaces
        return eq7(pressure, speed, temperature, mu_t0=mu_t0, factors=FACTORS[code],
                   dependencies=dependencies).item() - mu
    return brentq(residual, 1e-9, 2.0, xtol=1e-16, rtol=1e-15, maxiter=200)


@settings(max_examples=200, deadline=None)
@given(
    code=st.sampled_from([0, 1]),
    dependencies=st.sampled_from([DEPENDENCIES, ("velocity", "temperature"),
                                  ("pressure", "temperature"), ("temperature",),
                                  ("pressure", "velocity")]),
    pressure=st.floats(5e6, 90e6),
    speed=st.floats(1e-3, 1.0),
    rise=st.floats(0.0, 2e5),
    newest=st.floats(0.0, 5e-5),
    mu_t0=st.floats(0.03, 0.12),
)
def test_the_kernel_solves_eq7(code, dependencies, pressure, speed, rise, newest, mu_t0):
    values = {"initial_temperature": 20.0, "flux_coefficient": 2e-4, "factor_code": code,
              "reference_pressure": 60e6, "rate_parameter": 100.0, "mu_t0": mu_t0,
              "surfaces": 2.0, **{f"use_{d}": float(d in dependencies) for d in DEPENDENCIES}}
    parameters = pack_ptv(values)
    mu, dmu_dspeed, temperature, flux = ptv_friction(rise, True, parameters, newest, pressure,
                                                     speed)
    base = 20.0 + 2e-4 * rise
    expected = _fixed_point(code, dependencies, mu_t0, base, newest, pressure, speed, 2.0)
    assert mu == pytest.approx(expected, rel=1e-11)
    assert temperature == pytest.approx(base + newest * mu * pressure * speed / 2.0, rel=1e-12)
    assert flux == pytest.approx(mu * pressure * speed / 2.0, rel=1e-12)
    h = 1e-4 * speed  # central differences: truncation ~1e-9 relative, round-off ~1e-10
    slope = (_fixed_point(code, dependencies, mu_t0, base, newest, pressure, speed + h, 2.0)
             - _fixed_point(code, dependencies, mu_t0, base, newest, pressure, speed - h, 2.0)
             ) / (2.0 * h)
    assert dmu_dspeed == pytest.approx(slope, rel=1e-6, abs=1e-9)


@pytest.mark.parametrize("factors", ["paper", "kumar"])
def test_the_readable_element_packs_its_model_for_the_kernel(factors):
    """A first trial of the precise model: the contact takes the flux of Eq. 7's mu."""
    model = PTVFriction(mu_t0=0.075, heating=MonitorLine(), factors=factors)
    state = model.bind(contact_radius=0.15, travel=0.6)
    pressure, velocity, dt = 60e6, -0.3, 0.01
    trial = state.trial((0.0, 0.0), (velocity, 0.0), pressure, dt)
    newest = 2.0 * state.heating.coefficient * math.sqrt(dt)
    t0 = model.thermal.initial_temperature
    assert trial.heat_flux == pytest.approx(trial.mu * pressure * abs(velocity) / 2, rel=1e-12)
    assert trial.temperature == pytest.approx(t0 + newest * trial.heat_flux, rel=1e-12)
    reference = eq7(pressure, velocity, trial.temperature, mu_t0=0.075, factors=model.factors)
    assert trial.mu == pytest.approx(reference.item(), rel=1e-12)


@pytest.mark.parametrize("velocity", [0.8, -0.8, 0.05, -0.05])
def test_the_velocity_tangent_keeps_its_sign_on_a_hot_plate(velocity):
    """d mu / d v = d mu / d|v| sign(v), also where d mu / d|v| < 0 (a hot plate at speed: the
    newest flux heats it more than alpha(v) adds): the evaluator's d mu / d|v| keeps its sign."""
    state = PTVFriction(mu_t0=0.075, heating=MonitorLine()).bind(contact_radius=0.15, travel=0.6)
    position, speed, dt = 0.0, 0.5, 0.005
    for _ in range(2000):  # heat the plate: back and forth over 0.4 m at 0.5 m/s
        position += speed * dt
        speed = -speed if abs(position) > 0.2 else speed
        state.trial((position, 0.0), (speed, 0.0), 60e6, dt)
        state.commit()
    trial = state.trial((position, 0.0), (velocity, 0.0), 60e6, dt)
    h = 1e-6
    slope = (state.trial((position, 0.0), (velocity + h, 0.0), 60e6, dt).mu
             - state.trial((position, 0.0), (velocity - h, 0.0), 60e6, dt).mu) / (2 * h)
    assert trial.temperature > 100.0
    assert math.copysign(1.0, velocity) * trial.dmu_dspeed == pytest.approx(slope, rel=1e-6,
                                                                            abs=1e-10)
