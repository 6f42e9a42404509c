"""Dependency factors (Eq. 1-3 and Kumar et al. 2015): values by hand, derivatives by
finite differences, and the compiled scalar kernels against the vectorised API."""

from __future__ import annotations

import math

import numpy as np
import pytest

from isolator.compiled import kernels
from isolator.compiled.layout import pack_ptv
from isolator.factors import KumarFactors, PaperFactors, factor_set


def test_paper_factors_by_hand():
    f = PaperFactors()
    assert f.pressure(60e6)[0] == pytest.approx(2.03 * 60**-0.19 + 0.068, rel=1e-14)
    assert f.velocity(0.4)[0] == pytest.approx(1 - 0.55 * math.exp(-0.019 * 400), rel=1e-14)
    assert f.velocity(-0.4)[0] == f.velocity(0.4)[0]  # a function of the speed
    assert f.velocity(0.0)[0] == pytest.approx(0.45)
    assert f.temperature(20.0)[0] == pytest.approx(1.13 * math.exp(-0.14), rel=1e-14)


def test_kumar_factors_by_hand():
    f = KumarFactors(reference_pressure=50e6, rate_parameter=80.0)
    assert f.pressure(50e6)[0] == pytest.approx(1.0)
    assert f.pressure(100e6)[0] == pytest.approx(0.7)
    assert f.temperature(50.0)[0] == pytest.approx(0.789 * 1.1)
    assert f.velocity(0.1)[0] == pytest.approx(1 - 0.5 * math.exp(-8.0))
    assert factor_set("kumar", rate_parameter=80.0).rate_parameter == 80.0


@pytest.mark.parametrize("factors", [PaperFactors(), KumarFactors()], ids=["paper", "kumar"])
@pytest.mark.parametrize(("method", "x", "h"), [("pressure", 35e6, 1e2), ("velocity", 0.012, 1e-7),
                                                 ("temperature", 87.0, 1e-5)])
def test_derivatives_match_finite_differences(factors, method, x, h):
    fn = getattr(factors, method)
    numeric = (fn(x + h)[0] - fn(x - h)[0]) / (2 * h)
    assert fn(x)[1] == pytest.approx(numeric, rel=1e-7)


def test_vectorised_api_accepts_arrays():
    p = np.array([20e6, 60e6, 90e6])
    gamma, dgamma = PaperFactors().pressure(p)
    assert gamma.shape == (3,) and np.all(np.diff(gamma) < 0) and np.all(dgamma < 0)


@pytest.mark.parametrize("code", [0, 1])
def test_compiled_kernels_match_the_factor_sets(code):
    factors = PaperFactors() if code == 0 else KumarFactors()
    _, p_ref, rate = factors.kernel_parameters
    parameters = pack_ptv({"factor_code": code, "reference_pressure": p_ref,
                           "rate_parameter": rate, "mu_t0": 0.075, "use_pressure": 1.0,
                           "use_velocity": 1.0})
    for pressure, speed in [(30e6, 0.05), (60e6, 0.4), (85e6, 0.0)]:
        mu, dmu = kernels.cold_friction(parameters, pressure, speed)
        assert mu == pytest.approx(0.075 * factors.pressure(pressure)[0]
                                   * factors.velocity(speed)[0], rel=1e-13)
        assert dmu == pytest.approx(0.075 * factors.pressure(pressure)[0]
                                    * factors.velocity(speed)[1], rel=1e-13)
        py = kernels.cold_friction.py_func(parameters, pressure, speed)
        assert py == pytest.approx((mu, dmu), rel=1e-13)
    for t in (20.0, 150.0):
        assert kernels.temperature_factor(code, t)[0] == pytest.approx(
            factors.temperature(t)[0], rel=1e-13)
