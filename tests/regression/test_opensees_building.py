"""The five-storey building of ``examples/five_storey.toml`` under El Centro: ours against OpenSees.

Script: this file runs both live (no stored fixture), with openseespy 3.7.1.2 (OpenSees 3.7.1)
through :mod:`structures.opensees.building` and :mod:`structures.opensees.comparison` (the
building twin in one direction: the 3D model with Y and torsion restrained): 5 x 400 t
floors, 500 t base slab, fixed-base period 0.5 s, Rayleigh 2 % on modes 1 and 2, 6 bearings
(R_eff = 4.5 m, 300 mm slider, u_y = 0.5 mm), El Centro 1940 N-S (bundled), dt = 0.005 s,
Newmark average acceleration unless stated. Differences are OpenSees's relative to ours
(peak: max|x_OS| / max|x_ours| - 1; NRMSE: RMS difference / peak of ours).

Measured (openseespy 3.7.1.2):

- flatSliderBearing + linear spring W/R (N = W, our law), Coulomb: every history to 1e-12 of
  its peak; energy balance of the OpenSees histories 2e-12. Our damping network reproduces
  T^T C_fb T exactly, the mass-proportional part included (modal damping too: 7e-13).
- singleFPBearing Coulomb (N = W + F u/R): peak isolator displacement -0.036 %, base shear
  +0.105 % (the normal force is 0.11 % above W at the peak), NRMSE of the displacement
  0.026 %, of the base shear 0.042 %.
- HHT alpha = -0.05 (OpenSees ``HHT 0.95``), spring twin: peak displacement -0.005 %, NRMSE
  0.006 %: OpenSees evaluates the element at u_(n+alpha), ours weights the forces.
- VelDependent (paper's factors at the bearing's pressure, kInit from mu_slow): peak
  displacement -0.64 %, base shear -0.13 %, NRMSE of the displacement 1.1 %, of the base
  shear 5.3 % (the pre-sliding branch: ours mu(v) N z, OpenSees a fixed-stiffness spring
  capped at mu(v) N); with u_y = 0.1 mm: -0.031 %, +0.081 %, NRMSE 0.17 %.
- FPBearingPTV (6 parallel elements, first 15 s): peak displacement +1.9 %, base shear
  +0.74 %, NRMSE of the displacement 1.6 %; temperature peak 119.3 degC (ours 121.7), largest
  gap 7.1 degC. Of that gap, FPBearingPTV's rectangle rule accounts for up to 6.45 degC
  (the exact integral of its own flux exceeds its temperature by 0 ... 6.45 degC, below the
  bound -zeta(1/2) c q_max sqrt(dt) = 6.93 degC) and the different flux histories for the
  rest (exact integrals of the two fluxes differ by up to 4.9 degC); ours is the exact
  integral of its own flux to 5e-7 degC. Driven by OpenSees's own isolator history, our
  bearing's temperature is within 6.45 degC of FPBearingPTV's (below the bound).

Wall time (ours / OpenSees, same analysis; ours warmed up): about 0.02 with the compiled engine
(0.002 for FPBearingPTV, whose cost grows as the square of the steps), about 2 with the
reference (pure Python) engine (0.2 for FPBearingPTV); see docs/opensees_comparison.md.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import scipy.special

from groundmotions.bundled import load_bundled
from isolator.heating import exact_rise
from isolator.testrig import run_test
from structures.config import load_config
from structures.integrators import HHT
from structures.opensees.building import run_opensees
from structures.opensees.comparison import compare, comparison_bearing, run_comparison
from structures.opensees.singlefp import run_singlefp_normal

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "five_storey.toml"

PTV_DURATION = 15.0  # [s] of El Centro for FPBearingPTV (its cost grows as steps^2)
OPENSEES_PI = 22.0 / 7.0


@pytest.fixture(scope="module")
def config():
    return load_config(EXAMPLE)


@pytest.fixture(scope="module")
def elcentro():
    return load_bundled("elcentro")


def _compare(config, motion, model, pendulum="singlefp", integrator=None, **bearing_changes):
    bearing = replace(comparison_bearing(config, model), **bearing_changes)
    return run_comparison(config.building, bearing, motion, integrator or config.integrator,
                          n_bearings=config.n_bearings, dt=config.dt, pendulum=pendulum)


@pytest.fixture(scope="module")
def coulomb(ops, config, elcentro):
    return _compare(config, elcentro, "constant")


@pytest.fixture(scope="module")
def twin(ops, config, elcentro, coulomb):
    """flatSliderBearing + spring: OpenSees with exactly our model."""
    opensees = run_opensees(config.building, comparison_bearing(config, "constant"), elcentro,
                            config.integrator, n_bearings=config.n_bearings, dt=config.dt,
                            pendulum="spring")
    return coulomb.ours, opensees, compare(coulomb.ours, opensees)["difference"]


def _largest(difference):
    return max(abs(v) for k, v in difference.items() if k != "max_temperature_gap")


def _bearing(ds, name):
    """The history of one bearing, along x for a vector (the one bearing position)."""
    values = ds[name].values[:, 0]
    return values[:, 0] if values.ndim == 2 else values


# --- the same form as analysis.run ------------------------------------------------------------

def test_result_has_the_form_of_analysis_run(coulomb):
    ours, opensees = coulomb.ours, coulomb.opensees
    assert set(ours.data_vars) <= set(opensees.data_vars)
    for name in ours.data_vars:
        assert opensees[name].dims == ours[name].dims, name
        assert opensees[name].attrs["units"] == ours[name].attrs["units"], name
    assert set(ours.attrs) - {"engine"} <= set(opensees.attrs)
    assert opensees.sizes == ours.sizes
    assert np.array_equal(opensees["time"], ours["time"])
    assert opensees.attrs["success"] == 1 and opensees.attrs["subdivisions"] == 0


def test_spring_twin_reproduces_our_run_to_round_off(twin):
    ours, opensees, difference = twin
    assert _largest(difference) <= 1e-9  # measured 6e-12
    assert opensees.attrs["energy_balance_error"] <= 1e-9  # 2e-12: our matrices, its history
    for name in ("displacement", "storey_shear", "bearing_friction_force"):
        scale = float(np.max(np.abs(ours[name])))
        assert float(np.max(np.abs(opensees[name] - ours[name]))) <= 1e-9 * scale


def test_modal_damping_network_is_exact(ops, config, elcentro):
    from structures.shear_building import ModalDamping

    building = replace(config.building, damping=ModalDamping(0.05))
    result = run_comparison(building, comparison_bearing(config, "constant"),
                            elcentro.truncated(5.0), n_bearings=config.n_bearings,
                            dt=config.dt, pendulum="spring")
    assert _largest(result.summary["difference"]) <= 1e-9  # measured 7e-13


# --- singleFPBearing ----------------------------------------------------------------------------

def test_coulomb_building_agrees(coulomb):
    difference = coulomb.summary["difference"]
    assert abs(difference["peak_isolator_displacement"]) <= 0.01  # measured -0.036 %
    assert abs(difference["peak_base_shear"]) <= 0.01  # +0.105 %
    assert difference["nrmse_isolator_displacement"] <= 0.02  # 0.026 %
    assert difference["nrmse_base_shear"] <= 0.01  # 0.042 %


def test_singlefp_normal_force_coupling_explains_the_gap(coulomb, config):
    """SingleFPSimple2d: N = W + F u / R per element; at the peak base shear it lifts N by
    about the base-shear gap (ours keeps N = W)."""
    opensees = coulomb.opensees
    per_bearing = config.building.weight / config.n_bearings
    u, force = _bearing(opensees, "bearing_displacement"), _bearing(opensees, "bearing_force")
    expected = per_bearing + force * u / config.bearing_geometry["effective_radius"]
    normal = _bearing(opensees, "axial_load")
    assert np.max(np.abs(normal - expected)) <= 1e-9 * per_bearing
    k = int(np.argmax(np.abs(force)))
    lift = normal[k] / per_bearing - 1.0  # 0.11 %
    assert coulomb.summary["difference"]["peak_base_shear"] == pytest.approx(lift, rel=0.2)


def test_singlefp_normal_force_given_to_ours_closes_the_gap(ops, config, elcentro):
    """Ours given singleFPBearing's N (the diagnostic twin of structures.opensees.singlefp),
    first 10 s: the base-shear peak gap +0.105 % falls to 3e-6, its NRMSE 0.064 % to 0.0065 %,
    the displacement's 0.033 % to 0.002 %."""
    motion = elcentro.truncated(10.0)
    plain = _compare(config, motion, "constant")
    matched = run_singlefp_normal(config.building, comparison_bearing(config, "constant"),
                                  motion, config.integrator, n_bearings=config.n_bearings,
                                  dt=config.dt)
    close = compare(matched, plain.opensees)["difference"]
    normal = _bearing(plain.opensees, "axial_load")
    assert np.max(np.abs(_bearing(matched, "axial_load") - normal)) <= 1e-5 * normal.max()
    for key in ("peak_base_shear", "nrmse_base_shear", "nrmse_isolator_displacement"):
        assert abs(close[key]) < 0.2 * abs(plain.summary["difference"][key]), key


def test_hht_maps_to_opensees_alpha(ops, config, elcentro):
    result = _compare(config, elcentro, "constant", "spring", HHT(-0.05))
    assert "HHT" in result.opensees.attrs["integrator"]
    difference = result.summary["difference"]
    assert abs(difference["peak_isolator_displacement"]) <= 1e-3  # measured -4.5e-5
    assert difference["nrmse_isolator_displacement"] <= 1e-3  # 6.3e-5
    assert difference["nrmse_base_shear"] <= 2e-3  # 2.1e-4


def test_velocity_dependent_building_agrees(ops, config, elcentro):
    coarse = _compare(config, elcentro, "velocity").summary["difference"]
    assert abs(coarse["peak_isolator_displacement"]) <= 0.02  # measured -0.64 %
    assert abs(coarse["peak_base_shear"]) <= 0.02  # -0.13 %
    assert coarse["nrmse_isolator_displacement"] <= 0.02  # 1.1 %
    fine = _compare(config, elcentro, "velocity", yield_displacement=1.0e-4)
    fine = fine.summary["difference"]  # the pre-sliding branch shrinks with u_y
    assert fine["nrmse_isolator_displacement"] <= coarse["nrmse_isolator_displacement"] / 5
    assert abs(fine["peak_isolator_displacement"]) <= 1e-3  # -3.1e-4


# --- FPBearingPTV --------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def ptv(ops, config, elcentro):
    result = _compare(config, elcentro.truncated(PTV_DURATION), "ptv")
    opensees = result.opensees
    # FPBearingPTV stays at 20 degC on its first two steps and wherever u is exactly 0
    valid = np.ones(opensees.sizes["time"], dtype=bool)
    valid[:3] = False
    valid[_bearing(opensees, "bearing_displacement") == 0.0] = False
    return result, valid


def _exact(result, thermal):
    """Exact Eq. 4 at every sample for a run's piecewise-constant flux [degC]."""
    t, q = result["time"].values, _bearing(result, "heat_flux")
    return np.array([thermal.initial_temperature + exact_rise(t[: n + 1], q[1 : n + 1], t[n],
                                                              thermal)
                     for n in range(t.size)])


def _rectangle_bound(result, thermal, dt):
    """-zeta(1/2) c q_max sqrt(dt): most by which FPBearingPTV's rectangle rule undershoots."""
    c = math.sqrt(thermal.diffusivity / OPENSEES_PI) / thermal.conductivity
    return -scipy.special.zeta(0.5) * c * np.max(_bearing(result, "heat_flux")) * math.sqrt(dt)


def test_fpbearingptv_building_temperature(ptv, config):
    result, valid = ptv
    ours, opensees = result.ours, result.opensees
    thermal = comparison_bearing(config, "ptv").friction.thermal
    bound = _rectangle_bound(opensees, thermal, config.dt)  # 6.93 degC
    t = opensees["time"].values
    q, temperature = _bearing(opensees, "heat_flux"), _bearing(opensees, "temperature")
    c = math.sqrt(thermal.diffusivity / OPENSEES_PI) / thermal.conductivity
    rectangle = np.array([20.0 + c * np.sum(q[m:0:-1] * config.dt / np.sqrt(t[1 : m + 1]))
                          for m in range(t.size)])
    assert np.max(np.abs(rectangle - temperature)[valid]) <= 1e-8  # its own rule, re-summed
    exact_os, exact_ours = _exact(opensees, thermal), _exact(ours, thermal)
    shortfall = (exact_os - temperature)[valid]
    assert shortfall.min() >= -1e-9 and shortfall.max() <= bound  # 0 ... 6.45 degC
    assert np.max(np.abs(exact_ours - _bearing(ours, "temperature"))) <= 1e-5  # 5e-7: exact
    flux_part = np.max(np.abs(exact_os - exact_ours)[valid])  # 4.9 degC: different histories
    assert flux_part <= bound
    gap = np.abs(temperature - _bearing(ours, "temperature"))[valid]
    assert np.max(gap) <= 1.5 * bound  # 7.1 degC
    peak = result.summary["ours"]["max_temperature"] - result.summary["opensees"][
        "max_temperature"]
    assert 0.0 <= peak <= bound  # 2.4 degC: the rectangle rule undershoots


def test_fpbearingptv_temperature_on_the_same_isolator_history(ptv, config):
    """Driven by OpenSees's own isolator history, our bearing's temperature stays within
    the rectangle-rule bound of FPBearingPTV's (the flux differences left are 22/7, the
    previous step's mu and the predictor's speed)."""
    result, valid = ptv
    opensees = result.opensees
    bearing = comparison_bearing(config, "ptv")
    one = replace(bearing, axial_load=config.building.weight / config.n_bearings)
    replay = run_test(one, opensees["time"].values, _bearing(opensees, "bearing_displacement"),
                      opensees["velocity"].isel(floor=0, direction=0).values)
    bound = _rectangle_bound(opensees, bearing.friction.thermal, config.dt)
    gap = np.abs(replay.temperature - _bearing(opensees, "temperature"))[valid]
    assert np.max(gap) <= bound  # 6.45 against 6.93 degC


def test_fpbearingptv_building_response(ptv):
    result, _ = ptv
    difference = result.summary["difference"]
    # the temperature gap (<= 1.5 x 6.9 degC) moves mu by <= 0.4 %/degC through kT, and the
    # pre-sliding spring has a fixed stiffness: a few per cent on the displacement
    assert abs(difference["peak_isolator_displacement"]) <= 0.03  # measured +1.9 %
    assert abs(difference["peak_base_shear"]) <= 0.02  # +0.74 %
    assert difference["nrmse_isolator_displacement"] <= 0.03  # 1.6 %
    assert result.opensees.attrs["element"] == "6 x FPBearingPTV"


def test_wall_time_ratio_is_reported(coulomb, ptv):
    for summary in (coulomb.summary, ptv[0].summary):
        assert 0.0 < summary["wall_time_ratio"] < math.inf
        assert summary["wall_time_ratio"] == pytest.approx(
            summary["ours"]["wall_time"] / summary["opensees"]["wall_time"])
