"""Invariants of the DCFPB element under random histories (hypothesis)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from isolator.bearing import DCFPBearing
from isolator.friction import ConstantFriction, PTVFriction
from isolator.heating import CentrePoint, MonitorLine

N = 60e6 * math.pi * 0.15**2
MODELS = {
    "precise": PTVFriction(heating=MonitorLine()),
    "simplified": PTVFriction(heating=CentrePoint()),
    "constant": ConstantFriction(),
}

steps = st.lists(
    st.tuples(
        st.floats(-0.02, 0.02),  # displacement increment [m]
        st.floats(-0.6, 0.6),  # velocity [m/s]
        st.floats(1e-4, 0.02),  # time step [s]
    ),
    min_size=1,
    max_size=40,
)


def _drive(element, history):
    u = t = 0.0
    for du, v, dt in history:
        u = float(np.clip(u + du, -0.5, 0.5))
        t += dt
        element.set_trial(u, v, t)
        element.commit()
    return u, t


@settings(max_examples=40, deadline=None)
@given(history=steps, model=st.sampled_from(sorted(MODELS)), trial=st.tuples(
    st.floats(-0.02, 0.02), st.floats(-0.6, 0.6), st.floats(1e-4, 0.02)))
def test_set_trial_twice_equals_once_and_revert_restores(history, model, trial):
    element = DCFPBearing(4.5, 0.3, N, MODELS[model]).element()
    u, t = _drive(element, history)
    committed = element.committed
    heat_before = _heat(element)
    first = element.set_trial(u + trial[0], trial[1], t + trial[2])
    element.set_trial(u - trial[0], -trial[1], t + 2 * trial[2])  # another, discarded trial
    again = element.set_trial(u + trial[0], trial[1], t + trial[2])
    assert first == again
    element.revert()
    assert element.committed == committed
    assert element.trial_state == committed
    assert _same(heat_before, _heat(element))
    # the reverted element continues exactly like one that never saw the trials
    twin = DCFPBearing(4.5, 0.3, N, MODELS[model]).element()
    _drive(twin, history)
    assert element.set_trial(u + 0.01, 0.2, t + 0.005) == twin.set_trial(u + 0.01, 0.2, t + 0.005)


@settings(max_examples=40, deadline=None)
@given(history=steps, model=st.sampled_from(sorted(MODELS)))
def test_friction_force_never_exceeds_mu_N(history, model):
    element = DCFPBearing(4.5, 0.3, N, MODELS[model]).element()
    u = t = 0.0
    for du, v, dt in history:
        u, t = float(np.clip(u + du, -0.5, 0.5)), t + dt
        element.set_trial(u, v, t)
        element.commit()
        s = element.committed
        assert abs(s.friction_force) <= s.mu * s.axial_load * (1 + 1e-12)
        assert abs(s.force - s.friction_force - N * u / 4.5) <= 1e-9 * N
        assert s.temperature >= 20.0 - 1e-9


@settings(max_examples=25, deadline=None)
@given(history=steps)
def test_negated_history_negates_the_force(history):
    a = DCFPBearing(4.5, 0.3, N, MODELS["precise"]).element()
    b = DCFPBearing(4.5, 0.3, N, MODELS["precise"]).element()
    _drive(a, history)
    _drive(b, [(-du, -v, dt) for du, v, dt in history])
    assert math.isclose(a.committed.force, -b.committed.force, rel_tol=1e-9, abs_tol=1e-6)
    assert math.isclose(a.committed.temperature, b.committed.temperature, rel_tol=1e-9)


def _heat(element):
    heating = element.friction_state.heating if hasattr(element.friction_state, "heating") else None
    return None if heating is None else heating.snapshot()


def _same(a, b):
    if a is None or b is None:
        return a is b
    return np.array_equal(a[0], b[0]) and a[1] == b[1]
