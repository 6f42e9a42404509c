"""Building-level check: a computed shake-table response diagnosed against the constant model.

Script: the demo building (``examples/five_storey.toml``: five storeys on six DCFPBs,
R_eff = 4.5 m, 300 mm sliders) under the bundled El Centro 1940 N-S record, computed with the
precise model (pressure, velocity and temperature dependence; the contact heats by about
48 degC), stands in for a measured response: the isolator displacement and the force through
one bearing, through :mod:`structures.diagnosis.adapter`, with white noise of 0.5 % of the
peak force and 0.02 mm on the displacement. The diagnosis is told the constant model.

Measured: one test, so held out by alternate cycles; constant-model force NRMSE on the
sliding phase 0.208 (noise 0.009); verdict velocity, unexplained: low-speed drop 0.52
(Eq. 2: 0.55), transition velocity 45 mm/s (Eq. 2: 53 mm/s); held-out gap shrinks by 72 %,
per-cycle EDC error 13 % -> 2.9 %. Heating would close 91 % of what is left (5.5 % of the RMS
force), but on one irregular earthquake response its block statistic is z = 2.7, below the
second-effect threshold chosen on the validation panel (3.0), so it is left unexplained rather
than named; the test keeps that honest outcome. The pressure dependence cannot show: the axial
load of a bearing is constant in this model. About 6 s.
"""

from __future__ import annotations

import numpy as np
import pytest

from groundmotions.bundled import load_bundled
from isolator.diagnosis import BearingRecord, Campaign, diagnose
from structures.analysis import run
from structures.config import load_config
from structures.diagnosis.adapter import bearing_campaign, bearing_records
from tests.conftest import REPO_ROOT


@pytest.fixture(scope="module")
def response():
    config = load_config(REPO_ROOT / "examples" / "five_storey.toml")
    result = run(config.building, config.bearing("precise"), load_bundled("elcentro"),
                 config.integrator, n_bearings=config.n_bearings, dt=config.dt)
    assert result.attrs["success"]
    return result


@pytest.fixture(scope="module")
def diagnosis(response):
    clean = bearing_campaign([response]).tests[0]
    rng = np.random.default_rng(11)
    n = len(clean)
    measured = BearingRecord(
        clean.name, clean.time, clean.displacement + rng.normal(0.0, 2e-5, n),
        clean.force + rng.normal(0.0, 0.005 * np.max(np.abs(clean.force)), n),
        clean.axial_force, clean.velocity + rng.normal(0.0, 2e-3, n))
    campaign = Campaign((measured,), response.attrs["effective_radius"],
                        response.attrs["slider_diameter"])
    return diagnose(campaign, "constant")


def test_adapter_takes_one_bearing(response):
    (record,) = bearing_records(response)
    n = response.attrs["n_bearings"]
    assert np.allclose(record.force * n, response["base_shear"].values[:, 0])
    assert np.all(record.axial_force == response.attrs["axial_load_per_bearing"])
    assert record.velocity_measured
    (total,) = bearing_records(response, per_bearing=False, velocity=False)
    assert np.allclose(total.force, response["base_shear"].values[:, 0])
    assert not total.velocity_measured


def test_diagnosis_names_velocity_and_leaves_the_heating_unexplained(diagnosis):
    summary = diagnosis.to_json()
    assert summary["verdict"] == ["velocity", "unexplained"], summary["verdict"]
    chosen = summary["chosen"]
    assert chosen["shrink"] >= 0.6, chosen
    assert chosen["EDC_rms_error_after"] < 0.3 * chosen["EDC_rms_error_before"]
    velocity = chosen["parameters"]["velocity"]
    assert velocity["low_speed_drop"] == pytest.approx(0.55, abs=0.06)  # Eq. 2
    pressure = next(e for e in summary["effects"] if e["name"] == "pressure")
    assert pressure["role"].startswith("untestable")
    # heating is what is left: with velocity it closes most of the rest (z below 3)
    from isolator.diagnosis.selection import improvement

    stage = diagnosis.selection.stage
    extended = diagnosis.problem._extended(stage.work, diagnosis.selection.chosen,
                                           (stage.singles["heating"],))
    z, closes = improvement(stage.work, diagnosis.selection.chosen, extended)
    assert closes > 0.8 and 2.0 < z < diagnosis.selection.thresholds.second_z
