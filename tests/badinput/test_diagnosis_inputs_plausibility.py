"""Bad physical levels for ``dcfpb diagnose``: nothing silently wrong.

Every file here reads (finite numbers, increasing time, the columns named), so only the levels
it implies betray the mistake: time in milliseconds, force in kN, an axial load in kN, a
displacement in millimetres, a dead or sign-reversed force channel, a wrong R_eff or axial
load. Each case runs through the CLI entry point and must exit with status 2 before any
fitting, naming the file (and the manifest's test), the column or value and the likely
mistake. The positive controls: the good test diagnoses (status 0), and the checks pass on
strokes of 3-400 mm with u_y of 0.1-2 mm, on the real friction-damper data and on every case
of both validation panels.

The tests are made from a realistic history: a DCFPB (R_eff = 4.5 m, 300 mm slider, 60 MPa,
constant mu 0.04 at the design velocity) driven through three 150 mm sine cycles of 2.5 s at
100 Hz by the virtual test machine, with 0.5 % force noise and 0.02 mm displacement noise.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from dcfpb.cli import main
from isolator.bearing import DCFPBearing
from isolator.diagnosis import Campaign, DataError, diagnose, load_campaign
from isolator.diagnosis.data import BearingRecord
from isolator.experiments import protocol_bearing
from isolator.protocols import sine
from isolator.testrig import run_test

R_EFF = 4.5  # [m]
DIAMETER = 0.3  # [m]
EXIT_BAD_INPUT = 2


def _history(amplitude: float, period: float, cycles: int = 3, dt: float = 0.01,
             seed: int = 0, yield_displacement: float = 5.0e-4) -> dict[str, np.ndarray]:
    """A measured-looking test [s, m, N] and its axial load [N] (a constant column)."""
    bearing = protocol_bearing("constant", effective_radius=R_EFF, slider_diameter=DIAMETER)
    bearing = DCFPBearing(R_EFF, DIAMETER, bearing.axial_load, bearing.friction,
                          yield_displacement=yield_displacement, displacement_capacity=0.6)
    h = sine(amplitude, period, cycles, dt)
    r = run_test(bearing, h.time, h.displacement, h.velocity)
    rng = np.random.default_rng(seed)
    n = r.force.size
    return {"time": r.time, "displacement": r.displacement + rng.normal(0.0, 2e-5, n),
            "force": r.force + rng.normal(0.0, 0.005 * np.max(np.abs(r.force)), n),
            "axial_force": np.full(n, float(bearing.axial_load))}


def _write(path, columns: dict[str, np.ndarray]) -> str:
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
               header=",".join(columns), comments="", fmt="%.10g")
    return str(path)


@pytest.fixture(scope="module")
def real():
    """The realistic test: 150 mm, 2.5 s, 100 Hz."""
    return _history(0.15, 2.5)


@pytest.fixture(scope="module")
def axial(real) -> float:
    return float(real["axial_force"][0])


def _without_axial(columns: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    return {k: v for k, v in columns.items() if k != "axial_force"}


def _diagnose(files: list[str], *, radius: float = R_EFF, load: float | None = None,
              extra: tuple[str, ...] = ()) -> list[str]:
    args = ["diagnose", *files, "--model", "constant", "--effective-radius", str(radius),
            "--slider-diameter", str(DIAMETER), *extra]
    return args + (["--axial-load", repr(load)] if load is not None else [])


def _refused(args: list[str], capsys, *needles: str | re.Pattern) -> str:
    """Run the CLI; it must exit with status 2 and name every needle (text or pattern) on
    stderr, in one line."""
    status = main(args)
    err = capsys.readouterr().err
    assert status == EXIT_BAD_INPUT, err
    assert err.startswith("dcfpb diagnose: error: ") and err.count("\n") == 1, err
    for needle in needles:
        found = needle.search(err) if isinstance(needle, re.Pattern) else needle in err
        assert found, (needle, err)
    return err


# ---- positive controls -----------------------------------------------------------------

def test_the_good_test_is_diagnosed(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "good.csv", _without_axial(real))
    assert main(_diagnose([path], load=axial, extra=("--json",))) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["verdict"] == ["none"]
    assert out["baseline"]["parameters"]["mu"] == pytest.approx(0.04, rel=0.1)


@pytest.mark.shared
def test_the_real_friction_damper_data_passes_at_nominal_loads(shared_dir):
    """The real data's loops (backlash, rig oscillation, mu 0.01-0.13 at 100 kN) pass the
    checks at any nominal load from 30 to 300 kN, one test at a time and all together."""
    folder = shared_dir / "realdata" / "friction-damper" / "compact"
    files = sorted(folder.glob("*.csv.gz"))
    if len(files) < 3:
        pytest.skip(f"the compact friction-damper files are absent from {folder}")
    for nominal in (3.0e4, 1.0e5, 3.0e5):
        for path in files:
            load_campaign([path], effective_radius=math.inf, slider_diameter=0.05,
                          axial_load=nominal)
    campaign = load_campaign(files, effective_radius=math.inf, slider_diameter=0.05,
                             axial_load=1.0e5)
    assert len(campaign.tests) == len(files)


@pytest.mark.parametrize("yield_displacement", [1.0e-4, 2.0e-3])
@pytest.mark.parametrize("amplitude, period", [(0.003, 2.5), (0.005, 10.0), (0.01, 2.5),
                                               (0.05, 10.0), (0.4, 5.0)])
def test_short_and_long_strokes_pass(tmp_path, amplitude, period, yield_displacement):
    """A stroke of a few u_y is mostly pre-sliding transition: its loop must not be taken
    for a pendulum slope many times N / R_eff."""
    h = _history(amplitude, period, cycles=2, yield_displacement=yield_displacement)
    path = _write(tmp_path / "t.csv", h)
    campaign = load_campaign([path], effective_radius=R_EFF, slider_diameter=DIAMETER)
    assert campaign.tests[0].constant_axial_force


def test_every_panel_case_passes(tmp_path):
    """Both validation panels, all halves: 0.002-0.01 s steps, 16-630 mm/s, mu 0.02-0.08,
    slopes 0.94-1.8 times N / R_eff (the stiffness and geometry cases)."""
    from validation.diagnosis import outside, tuning
    from validation.diagnosis.score import load_case

    for module, name in ((tuning, "tuning"), (outside, "outside")):
        folder = tmp_path / name
        module.write_panel(folder, seed=2026)
        labels = json.loads((folder / "labels.json").read_text())
        for case in labels:
            campaign, _ = load_case(folder / case)
            assert campaign.tests


# ---- time -----------------------------------------------------------------------------

def test_time_in_milliseconds_at_100_hz(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "ms.csv", _without_axial(real) | {"time": 1e3 * real["time"]})
    _refused(_diagnose([path], load=axial), capsys, "ms.csv", "time looks like milliseconds",
             "column 'time'", "sample interval of 10 s", "at most 0.1 s", "divide it by 1000")


def test_time_in_milliseconds_at_20_khz(real, axial, tmp_path, capsys):
    """A fast rig in ms: a 0.05 'second' interval passes, the velocity does not."""
    time = np.arange(0.0, 2.5, 5.0e-5)
    columns = {"time": 1e3 * time}
    for key in ("displacement", "force"):
        columns[key] = np.interp(time, real["time"], real[key])
    path = _write(tmp_path / "fast_ms.csv", columns)
    _refused(_diagnose([path], load=axial), capsys, "fast_ms.csv",
             "time looks like milliseconds", "peak velocity |du/dt|",
             re.compile(r"is 0\.00038\d m/s, outside the 0\.001-5 m/s"), "divide it by 1000")


# ---- displacement ---------------------------------------------------------------------

def test_a_small_stroke_in_millimetres_is_too_fast(axial, tmp_path, capsys):
    """4 mm written as 4 'm' passes the 5 m limit but moves at 10 'm/s'."""
    small = _history(0.004, 2.5, seed=1)
    path = _write(tmp_path / "mm.csv", _without_axial(small)
                  | {"displacement": 1e3 * small["displacement"]})
    _refused(_diagnose([path], load=axial), capsys, "mm.csv", "displacement looks like mm",
             "peak velocity", "0.001-5 m/s", "divide it by 1000")


def test_a_slow_stroke_in_millimetres_has_a_thousandth_of_the_slope(axial, tmp_path,
                                                                    capsys):
    """3 mm at 10 s written in mm: a plausible 1.9 'm/s', but the pendulum slope is 1/1000."""
    slow = _history(0.003, 10.0, cycles=2, dt=0.02, seed=2)
    path = _write(tmp_path / "slow_mm.csv", _without_axial(slow)
                  | {"displacement": 1e3 * slow["displacement"]})
    _refused(_diagnose([path], load=axial), capsys, "slow_mm.csv",
             "displacement looks like mm", re.compile(r"0\.001\d* times the pendulum's"),
             "a factor of 3 either way", "divide it by 1000")


# ---- force ----------------------------------------------------------------------------

def test_force_in_kilonewtons(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "kN.csv", _without_axial(real) | {"force": real["force"] / 1e3})
    _refused(_diagnose([path], load=axial), capsys, "kN.csv", "column 'force'",
             "friction coefficient", re.compile(r"is 4\.0\de-05, outside the 0\.003-0\.8"),
             "force looks like kN: multiply it by 1000")


def test_an_all_zero_force_column(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "zero.csv", _without_axial(real)
                  | {"force": np.zeros_like(real["force"])})
    err = _refused(_diagnose([path], load=axial), capsys, "zero.csv",
                   "column 'force' is all zero", "must vary")
    assert "sign convention" not in err


def test_a_constant_force_column(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "flat.csv", _without_axial(real)
                  | {"force": np.full_like(real["force"], 1234.5)})
    _refused(_diagnose([path], load=axial), capsys, "flat.csv",
             "column 'force' is constant at 1234.5 N")


def test_a_force_channel_with_noise_only(real, axial, tmp_path, capsys):
    noise = np.random.default_rng(3).normal(0.0, 2.0e3, real["force"].size)
    path = _write(tmp_path / "noise.csv", _without_axial(real) | {"force": noise})
    _refused(_diagnose([path], load=axial), capsys, "noise.csv",
             "column 'force' shows no friction loop", "scatter")


def test_a_sign_reversed_force(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "reversed.csv", _without_axial(real) | {"force": -real["force"]})
    _refused(_diagnose([path], load=axial), capsys, "reversed.csv",
             "column 'force' looks sign-reversed", "pushes along the motion",
             "Multiply it by -1")


# ---- axial load -----------------------------------------------------------------------

def test_the_axial_load_flag_in_kilonewtons(real, axial, tmp_path, capsys):
    path = _write(tmp_path / "good.csv", _without_axial(real))
    _refused(_diagnose([path], load=axial / 1e3), capsys, "good.csv",
             "the axial load given (4241.15 N)",
             re.compile(r"is 40\.\d, outside the 0\.003-0\.8"),
             "the axial load given looks like kN: give it in N")


def test_an_axial_force_column_in_kilonewtons(real, tmp_path, capsys):
    path = _write(tmp_path / "axial_kN.csv", real | {"axial_force": real["axial_force"] / 1e3})
    _refused(_diagnose([path]), capsys, "axial_kN.csv", "column 'axial_force' (4241.15 N)",
             "column 'axial_force' looks like kN")


@pytest.mark.parametrize("factor, ratio", [(10.0, "0.1 times"), (0.1, "10 times")])
def test_an_axial_load_ten_times_off_is_not_blamed_on_an_effect(real, axial, tmp_path, capsys,
                                                                factor, ratio):
    """mu stays plausible (0.004 or 0.4); only the slope against N / R_eff shows it."""
    path = _write(tmp_path / "good.csv", _without_axial(real))
    err = _refused(_diagnose([path], load=factor * axial), capsys, "good.csv",
                   "R_eff or the axial load looks wrong", ratio,
                   re.compile(r"an axial load of 4\.2\d+e\+06 N at that R_eff"))
    assert "sign convention of 'force'." in err  # says what the diagnosis would have blamed


# ---- effective radius -----------------------------------------------------------------

@pytest.mark.parametrize("radius, ratio", [(1.0, r"0\.22\d"), (20.0, r"4\.4\d"),
                                           (0.3, r"0\.066\d")])
def test_a_wrong_effective_radius(real, axial, tmp_path, capsys, radius, ratio):
    """Not a 'stiffness' verdict, nor the sign convention: the radius is named, with the
    4.5 m the loops imply."""
    path = _write(tmp_path / "good.csv", _without_axial(real))
    _refused(_diagnose([path], radius=radius, load=axial), capsys, "good.csv",
             "R_eff or the axial load looks wrong", re.compile(ratio + " times the pendulum's"),
             f"R_eff = {radius:g} m", re.compile(r"implies R_eff = 4\.[45]\d* m at that load"))


# ---- manifests: the test is named -----------------------------------------------------

def _manifest_args(path) -> list[str]:
    return ["diagnose", "--manifest", str(path), "--model", "constant",
            "--effective-radius", str(R_EFF), "--slider-diameter", str(DIAMETER)]


def test_a_manifest_names_the_test_with_force_in_kilonewtons(real, axial, tmp_path, capsys):
    """One test in kN among tests in N mixes units; all of them in kN is refused by level."""
    _write(tmp_path / "a.csv", _without_axial(real))
    _write(tmp_path / "b.csv", _without_axial(real) | {"force": real["force"] / 1e3})
    (tmp_path / "m.csv").write_text(f"file,axial_load\na.csv,{axial}\nb.csv,{axial}\n")
    _refused(_manifest_args(tmp_path / "m.csv"), capsys, "m.csv: test 2 (b.csv): its peak "
             "force", "mixes units")
    (tmp_path / "m.csv").write_text(f"file,axial_load\nb.csv,{axial}\nb.csv,{axial}\n")
    _refused(_manifest_args(tmp_path / "m.csv"), capsys, "m.csv: test 1 (b.csv): the "
             "friction coefficient", "the manifest's axial_load (4.24115e+06 N)",
             "force looks like kN: multiply it by 1000")


def test_a_manifest_axial_load_in_kilonewtons(real, axial, tmp_path, capsys):
    _write(tmp_path / "a.csv", _without_axial(real))
    (tmp_path / "m.toml").write_text(
        f'effective_radius = {R_EFF}\nslider_diameter = {DIAMETER}\n'
        f'[[test]]\nfile = "a.csv"\naxial_load = {axial / 1e3}\n')
    args = ["diagnose", "--manifest", str(tmp_path / "m.toml"), "--model", "constant"]
    _refused(args, capsys, "m.toml: test 1 (a.csv)",
             "the manifest's axial_load looks like kN")


def test_a_manifest_all_in_milliseconds(real, axial, tmp_path, capsys):
    """Every test in ms: the campaign does not mix units, the levels still betray them."""
    ms = _without_axial(real) | {"time": 1e3 * real["time"]}
    _write(tmp_path / "a.csv", ms)
    _write(tmp_path / "b.csv", ms)
    (tmp_path / "m.csv").write_text(f"file,axial_load\na.csv,{axial}\nb.csv,{axial}\n")
    _refused(_manifest_args(tmp_path / "m.csv"), capsys, "m.csv: test 1 (a.csv)",
             "time looks like milliseconds", "column 'time'")


# ---- the library: a campaign built in memory gets the same cause -----------------------

def test_diagnose_on_a_campaign_in_memory_names_the_unit_not_the_sign(real):
    record = BearingRecord("kN test", real["time"], real["displacement"],
                           real["force"] / 1e3, real["axial_force"])
    with pytest.raises(DataError, match=r"test 'kN test': .*force looks like kN"):
        diagnose(Campaign((record,), R_EFF, DIAMETER), "constant")
