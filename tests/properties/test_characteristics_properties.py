"""Properties of the energy dissipated per cycle (EDC, the loop integral of F du).

Cycles are closed in displacement (both ends on the mid-level), so a constant force encloses no
area, the integral is linear in force, and turning the (u, F) plane by 180 degrees keeps the
orientation and area of every loop.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from isolator.characteristics import cycle_characteristics

SETTINGS = settings(max_examples=60, deadline=None)


@st.composite
def loops(draw: st.DrawFn, periodic: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """A sine displacement over several cycles and a hysteretic force with random content.

    With ``periodic``, the force repeats exactly every period (one random period tiled).
    """
    steps = draw(st.integers(20, 120))
    cycles = draw(st.integers(3, 6))
    phase = draw(st.floats(-np.pi, np.pi))
    amplitude = draw(st.floats(1e-3, 1.0))
    stiffness = draw(st.floats(0.0, 1e7))
    strength = draw(st.floats(1e2, 1e6))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    k = np.arange(cycles * steps + 1)
    angle = 2.0 * np.pi * (k % steps) / steps + phase  # exactly periodic samples
    u = amplitude * np.sin(angle)
    noise = rng.normal(0.0, 0.2 * strength, steps)[k % steps] if periodic else (
        rng.normal(0.0, 0.2 * strength, k.size)
    )  # fmt: skip
    force = stiffness * u + strength * np.sign(np.cos(angle)) + noise
    return u, force


def edc(u: np.ndarray, force: np.ndarray) -> np.ndarray:
    return np.array([c.EDC for c in cycle_characteristics(u, force)])


def scale(u: np.ndarray, force: np.ndarray) -> float:
    """Size of a loop integral's round-off: (max |F|) (peak-to-peak u) [J]."""
    return float(np.max(np.abs(force)) * np.ptp(u))


@SETTINGS
@given(loops(), st.floats(-1e7, 1e7))
def test_edc_is_invariant_under_a_force_offset(loop: tuple, offset: float) -> None:
    u, force = loop
    shifted = edc(u, force + offset)
    tolerance = 1e-12 * u.size * (scale(u, force) + abs(offset) * np.ptp(u))
    np.testing.assert_allclose(shifted, edc(u, force), rtol=0.0, atol=tolerance)


@SETTINGS
@given(loops(), st.floats(-1e3, 1e3).filter(lambda x: x == 0.0 or abs(x) > 1e-200))
def test_edc_scales_linearly_with_force(loop: tuple, factor: float) -> None:
    # factors below 1e-200 make subnormal products whose rounding no relative bound covers
    u, force = loop
    expected = factor * edc(u, force)
    tolerance = 1e-12 * u.size * abs(factor) * scale(u, force)
    np.testing.assert_allclose(edc(u, factor * force), expected, rtol=0.0, atol=tolerance)


@SETTINGS
@given(loops(periodic=True))
def test_edc_is_kept_when_both_displacement_and_force_change_sign(loop: tuple) -> None:
    # -u crosses upward where u crosses downward: the cycles start half a period apart, but
    # every cycle of a periodic history encloses the same loop.
    u, force = loop
    original, flipped = edc(u, force), edc(-u, -force)
    tolerance = 1e-12 * u.size * scale(u, force)
    np.testing.assert_allclose(original, original[0], rtol=0.0, atol=tolerance)
    np.testing.assert_allclose(flipped, original[0], rtol=0.0, atol=tolerance)


@SETTINGS
@given(loops(), st.floats(-1e7, 1e7))
def test_keff_and_post_yield_stiffness_ignore_a_force_offset(loop: tuple, offset: float) -> None:
    u, force = loop
    for a, b in zip(
        cycle_characteristics(u, force), cycle_characteristics(u, force + offset), strict=True
    ):
        assert b.Keff == pytest.approx(a.Keff, rel=1e-9, abs=1e-9 * abs(offset) / np.ptp(u))
        assert b.Kru == pytest.approx(a.Kru, rel=1e-9, abs=1e-6 * (abs(offset) + 1.0) / np.ptp(u))
        assert b.Krl == pytest.approx(a.Krl, rel=1e-9, abs=1e-6 * (abs(offset) + 1.0) / np.ptp(u))
