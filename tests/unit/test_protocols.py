"""Imposed displacement histories: sine, wind cycles, ASCE 7-16 prototype sequence."""

from __future__ import annotations

import numpy as np
import pytest

from isolator.protocols import (
    ImposedHistory,
    asce7_prototype_sequence,
    concatenate,
    hold,
    long_duration_cycles,
    sine,
    wind_cycles,
    wind_displacement_from_force,
)


def upward_crossings(u: np.ndarray) -> int:
    """Full cycles of a history that starts on zero rising and ends on zero: the upward
    crossings of zero, counting the start and not the end."""
    assert u[0] == 0.0 < u[1] and u[-1] == 0.0
    return 1 + int(np.count_nonzero((u[:-2] < 0.0) & (u[1:-1] >= 0.0)))


class TestSine:
    def test_peak_period_and_velocity(self) -> None:
        h = sine(0.15, 4.26, 3, 4.26 / 400)
        assert len(h) == 1201
        assert h.time[-1] == pytest.approx(3 * 4.26, rel=1e-14)
        assert h.displacement[0] == h.displacement[-1] == 0.0
        assert np.max(h.displacement) == pytest.approx(0.15, rel=1e-12)
        assert np.min(h.displacement) == pytest.approx(-0.15, rel=1e-12)
        assert np.max(h.velocity) == pytest.approx(2.0 * np.pi * 0.15 / 4.26, rel=1e-12)
        assert upward_crossings(h.displacement) == 3
        # One period apart, the state repeats.
        np.testing.assert_allclose(h.displacement[400:], h.displacement[:-400], atol=1e-15)

    def test_velocity_is_the_derivative_of_displacement(self) -> None:
        h = sine(0.1, 2.0, 2, 0.01)
        central = (h.displacement[2:] - h.displacement[:-2]) / (h.time[2:] - h.time[:-2])
        omega_dt = 2.0 * np.pi * 0.01 / 2.0
        # Central difference error: v (omega dt)^2 / 6.
        tolerance = 0.1 * 2.0 * np.pi / 2.0 * omega_dt**2 / 6.0 * 1.01
        np.testing.assert_allclose(central, h.velocity[1:-1], rtol=0, atol=tolerance)

    def test_step_that_does_not_divide_the_period(self) -> None:
        h = sine(0.1, 1.0, 1, 0.03, start_time=5.0)
        steps = np.diff(h.time)
        assert len(h) == 35  # ceil(1 / 0.03) = 34 equal steps, none longer than dt
        np.testing.assert_allclose(steps, 1.0 / 34, rtol=1e-12)
        assert (h.time[0], h.time[-1]) == (5.0, pytest.approx(6.0, rel=1e-14))
        assert h.displacement[-1] == 0.0

    @pytest.mark.parametrize(
        ("kwargs", "name", "error"),
        [
            ({"amplitude": 0.0}, "amplitude", ValueError),
            ({"period": -1.0}, "period", ValueError),
            ({"cycles": 0}, "cycles", ValueError),
            ({"cycles": 2.5}, "cycles", TypeError),
            ({"dt": 0.2}, "dt", ValueError),  # > period / 20
            ({"dt": 0.0}, "dt", ValueError),
            ({"start_time": np.nan}, "start_time", ValueError),
        ],
    )
    def test_errors_name_the_parameter(self, kwargs: dict, name: str, error: type) -> None:
        args = {"amplitude": 0.1, "period": 2.0, "cycles": 2, "dt": 0.01} | kwargs
        with pytest.raises(error, match=f"The '{name}' parameter of sine"):
            sine(**args)


class TestWind:
    def test_peak_velocity_of_test_t02(self) -> None:
        h = wind_cycles(0.01)
        assert np.max(np.abs(h.velocity)) == pytest.approx(0.015, rel=1e-12)
        assert np.max(h.displacement) == pytest.approx(0.01, rel=1e-3)
        period = 2.0 * np.pi * 0.01 / 0.015
        assert h.duration == pytest.approx(20 * period, rel=1e-12)
        assert upward_crossings(h.displacement) == 20
        assert h.segments == (("wind", 0, len(h)),)

    def test_displacement_from_force_lies_on_the_sliding_branch(self) -> None:
        n, r, mu = 3.0e6, 2.0, 0.04
        u = wind_displacement_from_force(2.0 * mu * n, n, r, mu)
        assert u == pytest.approx(mu * r)
        assert n * u / r + mu * n == pytest.approx(2.0 * mu * n)
        assert wind_displacement_from_force(mu * n, n, r, mu) == 0.0  # no sliding
        assert wind_displacement_from_force(0.5 * mu * n, n, r, mu) == 0.0
        with pytest.raises(ValueError, match=r"'friction_coefficient'.*Got 1.5"):
            wind_displacement_from_force(1.0, n, r, 1.5)
        with pytest.raises(ValueError, match="'effective_radius'"):
            wind_displacement_from_force(1.0, n, np.inf, mu)

    def test_errors(self) -> None:
        with pytest.raises(ValueError, match="'peak_velocity' parameter of wind_cycles"):
            wind_cycles(0.01, peak_velocity=0.0)
        with pytest.raises(ValueError, match="'dt' parameter of wind_cycles"):
            wind_cycles(0.001, dt=0.1)  # period 0.42 s


class TestPrototypeSequence:
    D_M, D_TM, T, DT = 0.2, 0.24, 4.26, 4.26 / 80

    def blocks(self, h: ImposedHistory) -> list[tuple[str, np.ndarray]]:
        return [(label, h.displacement[a:b]) for label, a, b in h.segments if label != "rest"]

    def test_items_cycles_and_amplitudes(self) -> None:
        h = asce7_prototype_sequence(
            self.D_M, self.D_TM, self.T, self.DT, wind_displacement=0.005, rest=10.0
        )
        expected = [
            ("wind", 20, 0.005),
            ("0.25 D_M", 3, 0.25 * self.D_M),
            ("0.5 D_M", 3, 0.5 * self.D_M),
            ("0.67 D_M", 3, 0.67 * self.D_M),
            ("1.0 D_M", 3, self.D_M),
            ("D_TM", 3, self.D_TM),
            ("0.75 D_TM", 10, 0.75 * self.D_TM),  # S_M1, S_MS, B_M not given: the minimum
        ]
        blocks = self.blocks(h)
        assert [label for label, _ in blocks] == [label for label, _, _ in expected]
        for (_, u), (_, cycles, amplitude) in zip(blocks, expected, strict=True):
            assert upward_crossings(u) == cycles
            assert np.max(np.abs(u)) == pytest.approx(amplitude, rel=1e-3)
            assert u[0] == u[-1] == 0.0
        rests = h.segment_slices("rest")
        assert len(rests) == 6
        for s in rests:
            assert h.time[s][-1] - h.time[s][0] == pytest.approx(10.0)
            assert not np.any(h.displacement[s]) and not np.any(h.velocity[s][1:-1])
        # One continuous history: the blocks tile it, sharing their joining samples.
        assert h.segments[0][1] == 0 and h.segments[-1][2] == len(h)
        assert all(a[2] - 1 == b[1] for a, b in zip(h.segments, h.segments[1:], strict=False))
        assert np.all(np.diff(h.time) > 0.0)
        assert np.max(np.abs(np.diff(h.displacement))) < 2.0 * np.pi * self.D_TM / 80

    def test_blocks_run_at_the_effective_period_and_wind_at_its_velocity(self) -> None:
        h = asce7_prototype_sequence(self.D_M, self.D_TM, self.T, self.DT, wind_displacement=0.01)
        for label, a, b in h.segments:
            block = ImposedHistory(h.time[a:b], h.displacement[a:b], h.velocity[a:b], label)
            period = block.duration / upward_crossings(block.displacement)
            if label == "wind":  # the last sample is shared with the next block
                assert np.max(np.abs(block.velocity[:-1])) == pytest.approx(0.015, rel=1e-12)
            else:
                assert period == pytest.approx(self.T, rel=1e-12)

    def test_long_duration_cycles_item_4(self) -> None:
        assert long_duration_cycles(None, None, None) == 10
        assert long_duration_cycles(0.6, 1.0, 1.0) == 18
        assert long_duration_cycles(0.5, 1.2, 1.0) == 13  # 12.5 rounded up
        assert long_duration_cycles(0.3, 1.5, 1.2) == 10  # 5, but not less than 10
        h = asce7_prototype_sequence(
            self.D_M, self.D_TM, self.T, self.DT, wind_displacement=0.0,
            S_M1=0.6, S_MS=1.0, B_M=1.0,
        )  # fmt: skip
        (last,) = h.segment_slices("0.75 D_TM")
        assert upward_crossings(h.displacement[last]) == 18
        assert "wind" not in [label for label, _, _ in h.segments]  # no sliding under wind

    def test_item_2b_is_one_cycle_per_multiple_down_then_up(self) -> None:
        h = asce7_prototype_sequence(
            self.D_M, self.D_TM, self.T, self.DT, wind_displacement=0.0, rest=5.0, item2="b"
        )
        labels = [label for label, _, _ in h.segments]
        down = ["1.0 D_M", "0.67 D_M", "0.5 D_M", "0.25 D_M"]
        assert labels == [*down, "rest", *down[::-1], "rest", "D_TM", "rest", "0.75 D_TM"]
        for label, u in self.blocks(h)[:8]:
            assert upward_crossings(u) == 1
            assert np.max(u) == pytest.approx(float(label.split()[0]) * self.D_M, rel=1e-3)

    @pytest.mark.parametrize(
        ("kwargs", "name"),
        [
            ({"maximum_displacement": -0.1}, "maximum_displacement"),
            ({"total_maximum_displacement": 0.1}, "total_maximum_displacement"),  # < D_M
            ({"period": 0.0}, "period"),
            ({"dt": 0.5}, "dt"),
            ({"wind_displacement": 0.0005}, "dt"),  # wind period 0.21 s needs dt <= 0.01 s
            ({"wind_displacement": -0.01}, "wind_displacement"),
            ({"S_M1": 0.6}, "S_MS"),  # all three or none
            ({"S_M1": 0.6, "S_MS": 1.0, "B_M": 3.0}, "B_M"),
            ({"rest": -1.0}, "rest"),
            ({"item2": "c"}, "item2"),
        ],
    )
    def test_errors_name_the_parameter(self, kwargs: dict, name: str) -> None:
        args = {
            "maximum_displacement": self.D_M,
            "total_maximum_displacement": self.D_TM,
            "period": self.T,
            "dt": self.DT,
            "wind_displacement": 0.005,
        } | kwargs
        with pytest.raises(ValueError, match=f"The '{name}' parameter of asce7_prototype_seq"):
            asce7_prototype_sequence(**args)


class TestHistoryAndConcatenate:
    def test_concatenate_joins_at_a_shared_sample(self) -> None:
        a, b = sine(0.1, 2.0, 1, 0.1), sine(0.2, 1.0, 2, 0.05, start_time=100.0)
        h = concatenate(a, hold(0.5, 0.1), b)
        assert len(h) == len(a) + 6 + len(b) - 2  # the rest: 5 steps of 0.1 s
        assert h.time[len(a) - 1] == pytest.approx(2.0)
        assert h.time[-1] == pytest.approx(4.5)
        # At a velocity jump the joining sample takes the midpoint of the jump.
        assert h.velocity[len(a) - 1] == pytest.approx(0.5 * a.velocity[-1], rel=1e-15)
        assert h.velocity[len(a) + 4] == pytest.approx(0.5 * b.velocity[0], rel=1e-15)
        np.testing.assert_array_equal(h.velocity[-len(b) + 1 :], b.velocity[1:])
        assert [label for label, _, _ in h.segments] == ["sine", "rest", "sine"]
        assert h.name == "sine + rest + sine"

    def test_concatenate_refuses_a_jump(self) -> None:
        a = sine(0.1, 2.0, 1, 0.1)
        shifted = ImposedHistory(a.time, a.displacement + 0.01, a.velocity, "shifted")
        with pytest.raises(ValueError, match=r"continuous in displacement.*history 1"):
            concatenate(a, shifted)

    def test_history_is_validated_and_read_only(self) -> None:
        t = np.linspace(0.0, 1.0, 5)
        with pytest.raises(ValueError, match=r"'time'.*strictly increasing"):
            ImposedHistory(t[::-1], t, t, "x")
        with pytest.raises(ValueError, match=r"'velocity'.*length of 'time'"):
            ImposedHistory(t, t, t[:-1], "x")
        with pytest.raises(ValueError, match="'segments'"):
            ImposedHistory(t, t, t, "x", (("a", 3, 9),))
        h = ImposedHistory(t, t, t, "x")
        with pytest.raises(ValueError, match="read-only"):
            h.displacement[0] = 1.0
