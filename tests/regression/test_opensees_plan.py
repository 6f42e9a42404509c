"""The building in plan against OpenSees 3D (issue 13 point 7, the building side).

Script: this file runs both live (no stored fixture), with openseespy 3.7.1.2 (OpenSees 3.7.1)
through :mod:`structures.opensees.building` and :mod:`structures.opensees.comparison`. The
building: 3 x 400 t floors, 500 t base slab, fixed-base period 0.5 s (x and y), Rayleigh 2 %
on modes 1 and 2; plan 18 m x 12 m on 6 bearings at x = -9, 0, 9 m and y = -6, 6 m from the
centre of stiffness; the centre of mass of every level at (0.9, 0.6) m, 5 % of the plan
dimensions; inertias and torsional stiffness from the rectangle. Bearings: R_eff = 4.5 m,
300 mm slider, u_y = 0.5 mm, Coulomb (the building file's constant model, mu = 0.0403),
each carrying its gravity share. Newmark average acceleration, dt = 5 ms. Both sides run
without overturning here (with it: tests/regression/test_opensees_overturning.py).
Differences are OpenSees's relative to ours (peak: max|x_OS| / max|x_ours| - 1 of a
resultant; NRMSE: RMS difference / peak of ours, per component).

Measured (openseespy 3.7.1.2):

- flatSliderBearing 3D + springs N_i / R (our law): every history to 1e-9 of its peak, with a
  vertical component too; the energy balance of the OpenSees histories closes to 1e-12. The
  rigid diaphragms, the masters at the centres of mass and the damping network are ours, with
  modal damping (5 % on every mode) as with Rayleigh's.
- singleFPBearing 3D, synthetic pair (Kanai-Tajimi, 8 s, PGA 4 m/s^2; 0.34 m): peak
  isolator displacement -0.38 %, centre -0.40 %, base shear +0.79 %; NRMSE of the bearing
  displacement x 0.21 %, y 0.18 %, base rotation 0.71 %. singleFPBearing's normal force is up
  to 0.89 % above the share (N = P + F . u / R), which is the base-shear gap.
- The same with a vertical (4 s, ratio 2/3): -0.18 %, +0.46 %, NRMSE 0.16 % / 0.15 %; its
  normal force less its lift is our axial load to 1e-8.
- With singleFPBearing's normal force given to ours (:mod:`structures.opensees.singlefp`):
  peak displacement -0.020 %, base shear +0.055 %, NRMSE 0.013 % / 0.043 % (the crossed radii
  and the return map are what is left).
- TAP094 (Chi-Chi, N and E) scaled by scale_suite to the ASCE 7-16 design spectrum S_DS = 1 g,
  S_D1 = 0.4 g, T_L = 8 s on RotD100 over (2.25, 5.33) s (factor 2.39), the 10 s from 3 s
  before its strongest sample (0.24 m): peak displacement -0.074 %, base shear +0.43 %,
  NRMSE 0.092 % / 0.080 %. Scaled to S_D1 = 0.6 g (factor 3.58, 0.41 m, u / R = 0.092) the
  base-shear gap reaches +0.996 %, the lift of singleFPBearing's N there (1.0 %); given that N,
  ours is within 0.094 %. The 1 % criterion on the base shear holds for u / R below about 0.09.
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest

from groundmotions.pairs import GroundMotionPair, read_pair
from groundmotions.records import GroundMotion
from groundmotions.scaling import asce7_design_spectrum, isolated_period_range, scale_suite
from groundmotions.synthetic import synthetic_pair
from isolator.bearing import DCFPBearing
from isolator.experiments import friction_model
from structures.analysis import run
from structures.opensees.building import run_opensees
from structures.opensees.comparison import compare, run_comparison
from structures.opensees.singlefp import run_singlefp_normal
from structures.plan import Plan
from structures.shear_building import ModalDamping, ShearBuilding

SHARED_PAIRS = Path(__file__).resolve().parents[3] / "shared" / "groundmotions" / "pairs"
DT = 0.005
S_D1 = 0.4  # [g] of the ASCE 7-16 design spectrum the recorded pair is scaled to (see below)
BEARINGS = [[-9.0, -6.0], [0.0, -6.0], [9.0, -6.0], [-9.0, 6.0], [0.0, 6.0], [9.0, 6.0]]
PEAKS = ("peak_isolator_displacement", "peak_corner_displacement", "peak_centre_displacement",
         "peak_base_shear")
NRMSES = ("nrmse_isolator_displacement_x", "nrmse_isolator_displacement_y",
          "nrmse_centre_displacement_x", "nrmse_centre_displacement_y")


@functools.cache
def _building(damping=None) -> ShearBuilding:
    plan = Plan(BEARINGS, eccentricity=(0.9, 0.6), dimensions=(18.0, 12.0),
                storey_heights=3.5)
    extra = {} if damping is None else {"damping": damping}
    return ShearBuilding.from_period([4e5, 4e5, 4e5], 0.5, base_mass=5e5, plan=plan, **extra)


@functools.cache
def _bearing() -> DCFPBearing:
    load = _building().weight / len(BEARINGS)
    friction = friction_model("constant", slider_diameter=0.3,
                              design_pressure=load / (np.pi * 0.15**2), design_velocity=0.4)
    return DCFPBearing(4.5, 0.3, friction=friction)


@functools.cache
def _synthetic(duration: float = 8.0, vertical: bool = False) -> GroundMotionPair:
    return synthetic_pair("kanai-tajimi", 3, duration=duration, dt=DT, target_pga=4.0,
                          ground_frequency=15.0, ground_damping=0.6,
                          vertical_ratio=2.0 / 3.0 if vertical else None)


def _relative(got: np.ndarray, expected: np.ndarray) -> float:
    return float(np.max(np.abs(got - expected)) / np.max(np.abs(expected)))


@pytest.mark.parametrize("damping", [None, ModalDamping(0.05)], ids=["rayleigh", "modal"])
def test_spring_twin_is_our_building_to_round_off(ops, damping):
    """flatSliderBearing 3D + linear springs N_i / R is our law and return map exactly, so
    what is left is the building: masses at the centres of mass under rigid diaphragms, the
    storeys, the damping network and the gravity shares."""
    pair = _synthetic() if damping is None else _synthetic(3.0)
    ours = run(_building(damping), _bearing(), pair, overturning=False, dt=DT)
    twin = run_opensees(_building(damping), _bearing(), pair, dt=DT, pendulum="spring",
                        overturning=False)
    assert ours.attrs["success"] and twin.attrs["success"]
    assert np.abs(ours["rotation"].values).max() > 1e-4  # the eccentricity turns it
    for name in ("displacement", "rotation", "bearing_displacement", "bearing_force",
                 "base_shear", "axial_load"):
        assert _relative(twin[name].values, ours[name].values) < 1e-7, name
    assert _relative(twin["absolute_acceleration"].values,
                     ours["absolute_acceleration"].values) < 1e-6
    assert twin.attrs["energy_balance_error"] < 1e-9


def test_vertical_component_loads_the_bearings_alike(ops):
    """The vertical is a quasi-static load N_i a_z / g on each bearing in OpenSees, our
    N_i (1 + a_z / g): singleFPBearing's normal force less its own lift F . u / R is our
    axial load. (The spring twin is not our law under a vertical: its springs keep N_i / R.)"""
    pair = _synthetic(4.0, vertical=True)
    comparison = run_comparison(_building(), _bearing(), pair, dt=DT, overturning=False)
    ours, opensees = comparison.ours, comparison.opensees
    load = ours["axial_load"].values
    assert np.ptp(load[:, 0]) > 0.2 * load[0, 0]  # the vertical moves the loads
    u = opensees["bearing_displacement"].values
    lever = u / np.sqrt(_bearing().effective_radius ** 2 - u[..., ::-1] ** 2)
    lift = np.sum(opensees["bearing_force"].values * lever, axis=-1)
    assert _relative(opensees["axial_load"].values - lift, load) < 1e-8
    _check_within_tolerance(comparison.summary)


def _check_within_tolerance(summary: dict) -> None:
    difference = summary["difference"]
    for key in PEAKS:
        assert abs(difference[key]) < 0.01, (key, difference[key])
    for key in NRMSES:
        assert difference[key] < 0.02, (key, difference[key])


def test_singlefp_under_a_synthetic_pair(ops):
    comparison = run_comparison(_building(), _bearing(), _synthetic(), dt=DT, overturning=False)
    summary = comparison.summary
    assert summary["ours"]["success"] and summary["opensees"]["success"]
    assert summary["opensees"]["element"] == "singleFPBearing 3D Coulomb"
    assert summary["ours"]["peak_isolator_displacement"] > 0.2  # the pendulums swing
    _check_within_tolerance(summary)
    # the gap is singleFPBearing's own: its normal force above the share, N = P + F . u / R
    lift = comparison.opensees["axial_load"].values / comparison.ours["axial_load"].values - 1
    assert 0.0 < summary["difference"]["peak_base_shear"] < 1.5 * lift.max()


def test_singlefp_normal_force_given_to_ours_closes_most_of_the_gap(ops):
    """Given singleFPBearing's N, ours differs by the crossed radii and the return map only."""
    pair = _synthetic(4.0)
    ours = run(_building(), _bearing(), pair, overturning=False, dt=DT)
    matched = run_singlefp_normal(_building(), _bearing(), pair, dt=DT)
    opensees = run_opensees(_building(), _bearing(), pair, dt=DT, overturning=False)
    plain, close = compare(ours, opensees), compare(matched, opensees)
    assert _relative(matched["axial_load"].values, opensees["axial_load"].values) < 1e-4
    for key in ("peak_base_shear", "nrmse_base_shear_x", "nrmse_base_shear_y",
                "nrmse_isolator_displacement_x", "nrmse_isolator_displacement_y"):
        assert abs(close["difference"][key]) < 0.2 * abs(plain["difference"][key]), key


@functools.cache
def _recorded_pair() -> GroundMotionPair:
    pair = read_pair(SHARED_PAIRS / "TAP094-N.AT2", SHARED_PAIRS / "TAP094-E.AT2")
    report = scale_suite([pair], asce7_design_spectrum(1.0, S_D1, 8.0),
                         isolated_period_range(3.0, 4.26), n_periods=8, angle_step=5.0)
    scaled = report.motions[0]
    start = max(int(np.argmax(np.hypot(scaled.x.acceleration, scaled.y.acceleration))
                    - 3.0 / scaled.dt), 0)
    window = slice(start, start + int(10.0 / scaled.dt) + 1)
    return GroundMotionPair(*(GroundMotion(m.acceleration[window], m.dt, m.name)
                              for m in (scaled.x, scaled.y)), name=f"{pair.name} scaled")


@pytest.mark.shared
def test_singlefp_under_a_scaled_recorded_pair(ops):
    if not SHARED_PAIRS.is_dir():
        pytest.skip(f"the recorded pairs of ../shared are absent ({SHARED_PAIRS})")
    comparison = run_comparison(_building(), _bearing(), _recorded_pair(), dt=DT,
                                overturning=False)
    summary = comparison.summary
    assert summary["ours"]["success"] and summary["opensees"]["success"]
    assert summary["ours"]["peak_isolator_displacement"] > 0.05
    _check_within_tolerance(summary)
