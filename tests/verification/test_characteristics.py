"""Cycle characteristics against closed-form loops (paper Section 3.1, Eq. 9-11, Fig. 7).

Rigid-plastic friction F = mu N sign(v) and the pendulum bilinear loop F = N u / R + mu N sign(v)
under a sine u = D sin(2 pi t / T) have EDC = 4 mu N D, Kru = Krl = N / R (0 for rigid-plastic),
Keff = N / R + mu N / D and beta_eff = 2 mu / (pi (D / R + mu)) (2 / pi for rigid-plastic).
"""

from __future__ import annotations

import numpy as np
import pytest

from isolator.characteristics import cycle_characteristics, find_cycles
from isolator.protocols import asce7_prototype_sequence

MU, N, R, D, T = 0.05, 2.0e6, 2.5, 0.2, 4.0  # [-], [N], [m], [m], [s]


def sine_history(steps_per_period: int, cycles: int, phase: float = 0.0):
    """u = D sin(2 pi t / T + phase), exact velocity, ``steps_per_period`` steps a period."""
    k = np.arange(cycles * steps_per_period + 1)
    angle = 2.0 * np.pi * (k % steps_per_period) / steps_per_period + phase
    time = T * k / steps_per_period
    return time, D * np.sin(angle), D * 2.0 * np.pi / T * np.cos(angle)


def elastoplastic_friction(displacement: np.ndarray, yield_displacement: float) -> np.ndarray:
    """Friction force of an elastic-perfectly-plastic spring (yield force mu N) [N]."""
    stiffness = MU * N / yield_displacement
    force = np.zeros_like(displacement)
    for i in range(1, displacement.size):
        trial = force[i - 1] + stiffness * (displacement[i] - displacement[i - 1])
        force[i] = np.clip(trial, -MU * N, MU * N)
    return force


def test_rigid_plastic_loop_edc_converges_at_second_order() -> None:
    # Steps per period = 2 mod 4: the reversals fall half-way between samples, where the
    # trapezoid misses mu N D (omega dt)^2 / 8 per reversal pair; crossings are interpolated.
    steps = np.array([22, 42, 82, 162, 322])
    errors = []
    for p in steps:
        time, u, v = sine_history(int(p), 3)
        cycles = cycle_characteristics(u, MU * N * np.sign(v), time)
        assert len(cycles) == 3
        edc = np.array([c.EDC for c in cycles])
        errors.append(abs(edc[1] / (4.0 * MU * N * D) - 1.0))
        np.testing.assert_allclose(edc, edc[1], rtol=1e-12)
        omega_dt = 2.0 * np.pi / p
        assert errors[-1] == pytest.approx(omega_dt**2 / 8.0, rel=0.02)
    order = np.polyfit(np.log(T / steps), np.log(errors), 1)[0]
    assert order == pytest.approx(2.0, abs=0.05)


def test_rigid_plastic_loop_has_no_post_yield_stiffness_and_two_over_pi_damping() -> None:
    time, u, v = sine_history(402, 2)
    for c in cycle_characteristics(u, MU * N * np.sign(v), time):
        assert abs(c.Kru) < 1e-9 * MU * N / D
        assert abs(c.Krl) < 1e-9 * MU * N / D
        assert c.Kra == pytest.approx(0.0, abs=1e-9 * MU * N / D)
        assert (c.Fmax, c.Fmin) == (MU * N, -MU * N)
        assert c.Keff == pytest.approx(MU * N / D, rel=1e-4)
        assert c.beta_eff == pytest.approx(2.0 / np.pi, rel=1e-4)
        assert c.stop_time - c.start_time == pytest.approx(T, rel=1e-12)


def test_bilinear_pendulum_loop_matches_closed_form() -> None:
    time, u, v = sine_history(402, 3)
    force = N * u / R + MU * N * np.sign(v)
    cycles = cycle_characteristics(u, force, time)
    assert [c.cycle for c in cycles] == [1, 2, 3]
    for c in cycles:
        assert c.Kru == pytest.approx(N / R, rel=1e-9)
        assert c.Krl == pytest.approx(N / R, rel=1e-9)
        assert c.Kra == pytest.approx(N / R, rel=1e-9)  # Eq. (9)
        assert c.Dmax == pytest.approx(D, rel=1e-4)
        assert c.Dmin == pytest.approx(-D, rel=1e-4)
        assert c.Keff == pytest.approx(N / R + MU * N / D, rel=1e-4)  # Eq. (10)
        edc = c.EDC
        assert edc == pytest.approx(4.0 * MU * N * D, rel=1e-4)
        assert c.beta_eff == pytest.approx(2.0 * MU / (np.pi * (D / R + MU)), rel=1e-4)  # (11)
        # The elastic part N u / R encloses no area: Eq. (11) from the closed form.
        assert c.beta_eff == pytest.approx(
            2.0 / np.pi * c.EDC / (c.Keff * (2.0 * D) ** 2), rel=1e-4
        )


def test_bilinear_loop_with_yield_displacement_loses_the_elastic_corners() -> None:
    yield_displacement = 0.01 * D
    time, u, _ = sine_history(800, 4)
    force = N * u / R + elastoplastic_friction(u, yield_displacement)
    cycles = cycle_characteristics(u, force, time)
    assert len(cycles) == 4
    for c in cycles[1:]:  # the first cycle starts from the virgin state
        assert c.Kru == pytest.approx(N / R, rel=1e-9)
        assert c.Krl == pytest.approx(N / R, rel=1e-9)
        assert c.Keff == pytest.approx(N / R + MU * N / D, rel=1e-9)
        edc = 4.0 * MU * N * (D - yield_displacement)
        assert c.EDC / edc == pytest.approx(1.0, rel=1e-4)
        beta = 2.0 / np.pi * edc / ((N / R + MU * N / D) * (2.0 * D) ** 2)
        assert c.beta_eff == pytest.approx(beta, rel=1e-4)


def test_edc_of_consecutive_cycles_adds_up_to_the_whole_loop_integral() -> None:
    time, u, v = sine_history(50, 4, phase=0.3)
    force = N * u / R + MU * N * np.sign(v) + 0.01 * MU * N * np.sin(7.0 * time)
    cycles = cycle_characteristics(u, force)
    first, last = cycles[0].start, cycles[-1].stop  # both crossings lie between two samples
    s0 = -u[first - 1] / (u[first] - u[first - 1])
    s1 = -u[last - 1] / (u[last] - u[last - 1])
    f0 = force[first - 1] + s0 * (force[first] - force[first - 1])
    f1 = force[last - 1] + s1 * (force[last] - force[last - 1])
    path_u = np.r_[0.0, u[first:last], 0.0]
    path_f = np.r_[f0, force[first:last], f1]
    whole = np.sum(0.5 * (path_f[1:] + path_f[:-1]) * np.diff(path_u))
    assert sum(c.EDC for c in cycles) == pytest.approx(whole, rel=1e-12)


def test_prototype_sequence_cycles_block_by_block() -> None:
    # Pendulum loop under the whole ASCE 7-16 sequence, rests included. The wind cycles (5 mm
    # against D_TM = 0.3 m) lie inside the noise band of the whole history: they are found when
    # their block is analysed alone. Piecewise-constant friction sampled symmetrically about
    # each peak gives EDC = 4 mu N Dmax exactly.
    h = asce7_prototype_sequence(0.25, 0.3, T, T / 202, wind_displacement=0.005, rest=5.0)
    force = N * h.displacement / R + MU * N * np.sign(h.velocity)
    cycles = cycle_characteristics(h.displacement, force, h.time)
    assert len(cycles) == 4 * 3 + 3 + 10
    periods = np.array([c.stop_time - c.start_time for c in cycles])
    np.testing.assert_allclose(periods[periods < T + 1.0], T, rtol=1e-9)
    np.testing.assert_allclose(periods[periods > T + 1.0], T + 5.0, rtol=1e-9)  # rest inside
    amplitudes = [0.25 * 0.25] * 3 + [0.5 * 0.25] * 3 + [0.67 * 0.25] * 3 + [0.25] * 3
    amplitudes += [0.3] * 3 + [0.75 * 0.3] * 10
    for c, amplitude in zip(cycles, amplitudes, strict=True):
        assert c.Dmax == pytest.approx(amplitude, rel=2e-4)
        assert c.EDC / (4.0 * MU * N * c.Dmax) == pytest.approx(1.0, rel=1e-12)
        assert c.Kru == pytest.approx(N / R, rel=1e-9)
        assert c.Krl == pytest.approx(N / R, rel=1e-9)
    (wind,) = h.segment_slices("wind")
    assert len(cycle_characteristics(h.displacement[wind], force[wind])) == 20


class TestFindCycles:
    def test_several_cycles_starting_on_the_level(self) -> None:
        _, u, _ = sine_history(40, 5)
        assert find_cycles(u) == [(40 * k, 40 * (k + 1)) for k in range(5)]

    def test_lead_in_and_partial_last_cycle_are_dropped(self) -> None:
        _, u, _ = sine_history(40, 5, phase=-np.pi / 2)  # starts at -D, crosses at T/4 + kT
        truncated = u[: 40 * 4 + 5]  # ends just before the crossing that closes the 4th cycle
        assert find_cycles(u) == [(10 + 40 * k, 50 + 40 * k) for k in range(4)]
        assert find_cycles(truncated) == [(10 + 40 * k, 50 + 40 * k) for k in range(3)]
        _, started_late, _ = sine_history(40, 3, phase=0.3)  # above the level, rising
        assert find_cycles(started_late) == [(39, 79), (79, 119)]  # crossings at k = 38.09 + 40 j

    def test_offset_is_handled_by_the_median_level(self) -> None:
        _, u, _ = sine_history(40, 4, phase=-np.pi / 2)
        shifted = u + 0.8 * D
        assert find_cycles(shifted) == []  # 0.2 D below zero against 1.8 D above
        assert find_cycles(shifted, mid_level="median") == find_cycles(u)
        assert find_cycles(shifted, mid_level=0.8 * D) == find_cycles(u)
        assert find_cycles(u + 0.1 * D) != []  # 0.9 / 1.1 > 0.3: still balanced

    def test_noise_does_not_split_or_merge_cycles(self) -> None:
        _, u, _ = sine_history(400, 6, phase=-np.pi / 2)
        rng = np.random.default_rng(20240612)
        noisy = u + rng.normal(0.0, 0.02 * D, u.size)  # re-crosses the level near each crossing
        clean = find_cycles(u)
        found = find_cycles(noisy)
        assert len(found) == len(clean) == 5
        for (a, b), (c, d) in zip(found, clean, strict=True):
            assert abs(a - c) <= 5 and abs(b - d) <= 5  # 5 samples = 0.08 rad of phase
        # Without the band, spurious upward crossings cut the history into wrong cycles.
        unbanded = find_cycles(noisy, crossing_band=0.0)
        assert any(abs(b - a - 400) > 10 for a, b in unbanded)

    def test_varying_amplitude(self) -> None:
        time, u, _ = sine_history(60, 6)
        growing = u * (1.0 + 0.5 * time / T)  # amplitude from D to 4 D
        cycles = cycle_characteristics(growing, N * growing / R)
        assert [(c.start, c.stop) for c in cycles] == [(60 * k, 60 * (k + 1)) for k in range(6)]
        assert np.all(np.diff([c.Dmax for c in cycles]) > 0.4 * D)


class TestErrors:
    def test_no_complete_cycle(self) -> None:
        _, u, v = sine_history(40, 1)
        with pytest.raises(ValueError, match=r"'displacement'.*at least one complete cycle"):
            cycle_characteristics(u[:30], np.sign(v[:30]))

    def test_mismatched_or_bad_arrays_name_the_parameter(self) -> None:
        _, u, v = sine_history(40, 2)
        with pytest.raises(ValueError, match="'force' parameter of cycle_characteristics"):
            cycle_characteristics(u, v[:-1])
        bad = v.copy()
        bad[7] = np.nan
        with pytest.raises(ValueError, match=r"'force'.*index 7"):
            cycle_characteristics(u, bad)
        with pytest.raises(ValueError, match="'time' parameter"):
            cycle_characteristics(u, v, np.zeros_like(u))
        with pytest.raises(ValueError, match=r"'transition_fraction'.*0, 0.5"):
            cycle_characteristics(u, v, transition_fraction=0.5)
        with pytest.raises(ValueError, match="'mid_level'"):
            find_cycles(u, mid_level="mean")
        with pytest.raises(ValueError, match="'min_excursion'"):
            find_cycles(u, min_excursion=1.5)

    def test_too_few_samples_on_a_branch(self) -> None:
        _, u, v = sine_history(20, 2)
        with pytest.raises(ValueError, match=r"upper branch.*transition_fraction"):
            cycle_characteristics(u, np.sign(v), transition_fraction=0.49)
