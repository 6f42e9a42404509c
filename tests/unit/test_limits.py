"""Run-length limits (:mod:`isolator.limits`, :mod:`structures.limits`): the step count and the
memory estimated before a run, refused past ``max_steps`` or the memory available, for the
library calls as for the command line."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest

from dcfpb.common.errors import InputError
from groundmotions.records import GroundMotion
from isolator.limits import DEFAULT_MAX_STEPS, available_memory, check_steps, history_steps
from isolator.protocols import hold, sine
from structures.limits import building_fields, check_run, fixed_base_fields, run_steps

REPO = Path(__file__).resolve().parents[2]


def _meminfo(tmp_path: Path, kilobytes: int) -> Path:
    path = tmp_path / "meminfo"
    path.write_text(f"MemTotal:       16000000 kB\nMemFree:         1000 kB\n"
                    f"MemAvailable:   {kilobytes} kB\n")
    return path


def _motion(dt: float, npts: int = 1001) -> GroundMotion:
    return GroundMotion(np.zeros(npts), dt, name="quiet")


def test_default_limit():
    assert DEFAULT_MAX_STEPS == 2_000_000


def test_available_memory_reads_memavailable(tmp_path):
    assert available_memory(_meminfo(tmp_path, 2048)) == 2048 * 1024
    assert available_memory(tmp_path / "absent") is None
    (tmp_path / "odd").write_text("MemTotal: 5 kB\n")
    assert available_memory(tmp_path / "odd") is None


def test_check_steps_past_the_limit_names_steps_source_and_remedy(tmp_path):
    with pytest.raises(InputError) as excinfo:
        check_steps(3_000_000, what="The run", duration=15_000.0, dt=0.005, bytes_per_step=8,
                    max_steps=2_000_000, raise_with="--max-steps",
                    meminfo=_meminfo(tmp_path, 10**9))
    message = str(excinfo.value)
    assert message.startswith("The run would take 3,000,000 steps (15000 s at dt = 0.005 s), "
                              "past the limit of 2,000,000 steps, and hold about 24 MB.")
    assert message.endswith("raise the limit with --max-steps (at least 3,000,000).")


def test_check_steps_refuses_what_the_memory_cannot_hold(tmp_path):
    check_steps(1000, what="The run", duration=10.0, dt=0.01, bytes_per_step=1000,
                max_steps=10**9, raise_with="x", meminfo=_meminfo(tmp_path, 1000))
    with pytest.raises(InputError, match=r"hold about 1.1 MB, more than the 1.02 MB of memory "
                       "available. Check the duration and the time step."):
        check_steps(1001, what="The run", duration=10.0, dt=0.01, bytes_per_step=1100,
                    max_steps=10**9, raise_with="x", meminfo=_meminfo(tmp_path, 1000))
    # no /proc/meminfo: the memory check is skipped
    check_steps(10**6, what="The run", duration=1.0, dt=1e-6, bytes_per_step=10**9,
                max_steps=10**9, raise_with="x", meminfo=tmp_path / "absent")


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, None])
def test_max_steps_must_be_a_positive_integer(bad):
    with pytest.raises(InputError, match=r"--max-steps must be an integer in \[1, inf\)"):
        check_steps(10, what="x", duration=1.0, dt=0.1, bytes_per_step=8, max_steps=bad,
                    raise_with="--max-steps")


def test_history_steps_are_the_sampling_convention():
    assert history_steps(12.78, 0.005) == 2556  # a step that divides the duration fits
    assert history_steps(1.0, 0.3) == 4 and history_steps(1e-9, 1.0) == 1
    with pytest.raises(InputError, match="past the limit of 100 steps"):
        history_steps(12.78, 0.005, max_steps=100)
    with pytest.raises(InputError, match="9,223,372,036,854,775,807 steps"):
        history_steps(1.0, 1e-320)  # duration / dt is inf


def test_sine_and_hold_are_bounded_before_any_array_is_made():
    assert len(sine(0.3, 4.26, 3, 0.005, max_steps=2556)) == 2557
    start = time.perf_counter()
    with pytest.raises(InputError, match=r"85,200,000 steps \(426000 s at dt = 0.005 s\)"):
        sine(0.3, 4.26, 100_000, 0.005)
    with pytest.raises(InputError, match="past the limit of 2,000,000 steps"):
        hold(1e6, 0.001)
    assert time.perf_counter() - start < 1.0


def test_fields_per_step_follow_the_dataset_and_the_engine():
    # five storeys in one direction: Dataset 3 x 6 levels + 2 x 5 storeys + 7 of the one
    # bearing position + 2 (base shear, ground) + 8 = 45, engine 4 x 6 + 10 per bearing
    # position + 7 = 41
    assert building_fields(5) == 86 and fixed_base_fields(5) == 38


def test_run_steps_of_the_record_or_a_finer_step():
    motion = _motion(0.02)  # 20 s
    assert run_steps(motion, None) == (1000, 0.02)
    assert run_steps(motion, 0.02) == (1000, 0.02)
    assert run_steps(motion, 0.005) == (4000, 0.005)
    with pytest.raises(ValueError, match=r"'dt' parameter of run must be a float in \(0, 0.02\]"):
        run_steps(motion, 0.05)


def test_check_run_names_the_record_duration_and_dt():
    with pytest.raises(InputError, match=r"The building run would take 4,000 steps \(20 s at "
                       r"dt = 0.005 s\), past the limit of 3,999 steps.*DT in its header.*the "
                       r"max_steps argument of structures.analysis.run"):
        check_run(_motion(0.02), 0.005, building_fields(5), max_steps=3999)
    assert check_run(_motion(0.02), 0.005, building_fields(5), max_steps=4000) == 4000


def test_library_run_is_refused_before_any_work():
    from structures.analysis import run
    from structures.config import load_config
    from structures.fixed_base import run_fixed_base

    config = load_config(REPO / "examples" / "five_storey.toml")
    motion = GroundMotion(np.zeros(1559), 100.0, name="DT = 100 s")  # 155,800 s
    start = time.perf_counter()
    with pytest.raises(InputError, match=r"31,160,000 steps \(155800 s at dt = 0.005 s\)"):
        run(config.building, config.bearing("constant"), motion, n_bearings=6, dt=0.005)
    with pytest.raises(InputError, match="past the limit of 1,000 steps"):
        run(config.building, config.bearing("constant"), _motion(0.02), n_bearings=6,
            dt=0.01, max_steps=1000)
    with pytest.raises(InputError, match="The fixed-base run would take 31,160,000 steps"):
        run_fixed_base(config.building, motion, dt=0.005)
    assert time.perf_counter() - start < 5.0
