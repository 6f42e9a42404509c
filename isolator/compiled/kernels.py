"""Compiled kernels of the isolator's hot path, with the same functions in plain Python.

The contact temperature's history part, the exponential-sum state update and the implicit
solve of mu = mu_cold beta(T(mu)). With numba they are compiled on first use and cached on
disk; without it, or with ``DCFPB_DISABLE_NUMBA=1``, the same source runs as plain Python.
Every compiled function keeps its Python original as ``py_func``."""

from __future__ import annotations

import os

import numpy as np

from isolator.compiled import layout as L
from isolator.compiled.layout import pack_ptv
from isolator.factors import (
    kumar_pressure_raw,
    kumar_temperature_raw,
    kumar_velocity_raw,
    paper_pressure_raw,
    paper_temperature_raw,
    paper_velocity_raw,
)

try:  # pragma: no cover - exercised by whichever environment runs the tests
    if os.environ.get("DCFPB_DISABLE_NUMBA", "") not in ("", "0"):
        raise ImportError("disabled by DCFPB_DISABLE_NUMBA")
    import numba

    from isolator.compiled.freshness import install

    install()  # a cached function is stale when any module of ours it imports changed
    COMPILED = True

    def jit(function):
        """Compile ``function`` with numba, cached on disk, without the unused C wrapper."""
        return numba.njit(cache=True, nogil=True, no_cfunc_wrapper=True)(function)

    def jit_unmanaged(function):
        """:func:`jit` with numba's reference counting (NRT) off, for functions that allocate
        nothing and only touch arrays their caller keeps alive: no counting to compile or run."""
        return numba.njit(cache=True, nogil=True, no_cfunc_wrapper=True, _nrt=False)(function)

    def jit_inner(function):
        """:func:`jit_unmanaged` without the wrapper that Python calls, for a function that only
        compiled code calls, through :func:`isolator.compiled.linking.separately` (whose
        stand-in, called from Python, compiles a twin with the wrapper). Called from Python
        itself, the compiled function crashes the process: only its stand-in may call it."""
        return numba.njit(cache=True, nogil=True, no_cfunc_wrapper=True, _nrt=False,
                          no_cpython_wrapper=True)(function)

except ImportError:  # pragma: no cover
    COMPILED = False

    def jit(function):
        """Without numba: the plain function, with ``py_func`` pointing at itself."""
        function.py_func = function
        return function

    jit_unmanaged = jit_inner = jit


_paper_pressure = jit(paper_pressure_raw)
_paper_velocity = jit(paper_velocity_raw)
_paper_temperature = jit(paper_temperature_raw)
_kumar_pressure = jit(kumar_pressure_raw)
_kumar_velocity = jit(kumar_velocity_raw)
_kumar_temperature = jit(kumar_temperature_raw)


@jit
def temperature_factor(code, temperature):
    """(beta, d beta / d T) of factor set ``code`` (0 paper, 1 Kumar)."""
    if code == 0:
        return _paper_temperature(temperature)
    return _kumar_temperature(temperature)


@jit
def cold_friction(parameters, pressure, speed):
    """mu_t0 gamma(p) alpha(|v|) and its derivative with respect to |v| [s/m]: Eq. 7 without the
    temperature, for the friction constants ``parameters``
    (:func:`~isolator.compiled.layout.pack_ptv`), a contact pressure [Pa] and a speed [m/s]."""
    gamma = 1.0
    alpha = 1.0
    dalpha = 0.0
    use_pressure = parameters[L.USE_PRESSURE] != 0.0
    use_velocity = parameters[L.USE_VELOCITY] != 0.0
    if int(parameters[L.FACTOR_CODE]) == 0:
        if use_pressure:
            gamma = _paper_pressure(pressure)[0]
        if use_velocity:
            alpha, dalpha = _paper_velocity(speed)
    else:
        if use_pressure:
            gamma = _kumar_pressure(pressure, parameters[L.REFERENCE_PRESSURE])[0]
        if use_velocity:
            alpha, dalpha = _kumar_velocity(speed, parameters[L.RATE_PARAMETER])
    mu_t0 = parameters[L.MU_T0]
    return mu_t0 * gamma * alpha, mu_t0 * gamma * dalpha


@jit
def contact_history(states, weighted_decay, lo, hi):
    """Mean over points ``lo:hi`` of sum_k w_k exp(-s_k dt) G_jk [W s^0.5 / m^2]."""
    if hi <= lo:
        return 0.0
    n_terms = weighted_decay.shape[0]
    column_sums = np.zeros(n_terms)
    for j in range(lo, hi):  # sum the rows first: this inner loop vectorises
        for k in range(n_terms):
            column_sums[k] += states[j, k]
    total = 0.0
    for k in range(n_terms):
        total += column_sums[k] * weighted_decay[k]
    return total / (hi - lo)


@jit
def advance_states(states, step, lo, hi, heated_lo, heated_hi, flux):
    """G_jk <- exp(-s_k dt) G_jk + q (1 - exp(-s_k dt)) / s_k in place (``step``: the two
    factors, shape (2, K)); the flux ``q`` [W/m^2] enters points ``heated_lo:heated_hi`` only.
    ``[lo, hi)``, the points ever heated (the others are zero), is returned grown by those."""
    if flux != 0.0 and heated_hi > heated_lo:
        lo = min(lo, heated_lo)
        hi = max(hi, heated_hi)
    decay = step[0]
    gain = step[1]
    n_terms = decay.shape[0]
    for j in range(lo, hi):
        if heated_lo <= j < heated_hi and flux != 0.0:
            for k in range(n_terms):
                states[j, k] = states[j, k] * decay[k] + flux * gain[k]
        else:
            for k in range(n_terms):
                states[j, k] *= decay[k]
    return lo, hi


@jit
def solve_friction(code, mu_cold, dmu_cold, use_temperature, base, a, newest_per_mu_speed):
    """Solve mu = mu_cold beta(base + a mu) by Newton: ``(mu, dmu_dspeed, temperature)``.

    ``code``: factor set (0 paper, 1 Kumar); ``mu_cold``, ``dmu_cold``: mu_t0 gamma alpha and
    its derivative with respect to |v| [s/m]; ``use_temperature``: whether beta acts; ``base``:
    the contact temperature without the newest interval [degC]; ``a``: d T / d mu through that
    interval's flux [degC]; ``newest_per_mu_speed``: a / |v| [degC s/m].
    """
    if not use_temperature:
        return mu_cold, dmu_cold, base + a * mu_cold
    beta, dbeta = temperature_factor(code, base)
    mu = mu_cold * beta
    for _ in range(50):
        beta, dbeta = temperature_factor(code, base + a * mu)
        step = (mu - mu_cold * beta) / (1.0 - mu_cold * dbeta * a)
        mu -= step
        if abs(step) <= 1e-15 * abs(mu):
            break
    temperature = base + a * mu
    beta, dbeta = temperature_factor(code, temperature)
    coupling = mu_cold * dbeta  # d mu / d T at fixed velocity
    dmu_dspeed = (dmu_cold * beta + coupling * newest_per_mu_speed * mu) / (1.0 - coupling * a)
    return mu, dmu_dspeed, temperature


@jit
def initial_friction(parameters, pressure, speed):
    """Eq. 7 at the initial temperature T0 (no heating, or no time since the last commit):
    ``(mu, d mu / d|v| [s/m], T0 [degC])`` for the constants ``parameters``."""
    mu_cold, dmu_cold = cold_friction(parameters, pressure, speed)
    return solve_friction(int(parameters[L.FACTOR_CODE]), mu_cold, dmu_cold,
                          parameters[L.USE_TEMPERATURE] != 0.0,
                          parameters[L.INITIAL_TEMPERATURE], 0.0, 0.0)


@jit
def heated_window(position, first, spacing, n_points, half_width, average_over_contact):
    """``(lo, hi, inside)``: points ``[lo, hi)`` within ``half_width`` of the slider centre at
    ``position`` [m], on a line of points at ``first + j spacing`` (``average_over_contact``)
    or the single centre point (``(0, 1)`` covered, ``(0, 0)`` not). Closed window (Eq. 5, 6:
    delta <= half width, slack 1e-9 of a spacing); ``inside`` False past either end of the line.
    """
    if average_over_contact:
        lo = int(np.ceil((position - half_width - first) / spacing - 1e-9))
        hi = int(np.floor((position + half_width - first) / spacing + 1e-9)) + 1
        return lo, hi, (lo > 0 and hi < n_points)
    if abs(position) <= half_width * (1.0 + 1e-12):
        return 0, 1, True
    return 0, 0, True


@jit
def ptv_friction(rise, heated, parameters, newest, pressure, speed):
    """Eq. 7 for a contact whose temperature history part is ``rise``, the end of a PTV trial:
    ``(mu, dmu_dspeed, temperature, flux)``.

    The contact temperature is T0 + c ``rise`` (:func:`contact_history` over the averaged
    points) plus the newest interval's share, whose flux q = mu p |v| / surfaces enters only
    when those points take it (``heated``); the other arguments as for :func:`ptv_trial`.
    """
    fraction = 1.0 if heated else 0.0
    base = parameters[L.INITIAL_TEMPERATURE] + parameters[L.FLUX_COEFFICIENT] * rise
    code = int(parameters[L.FACTOR_CODE])
    mu_cold, dmu_cold = cold_friction(parameters, pressure, speed)
    flux_per_mu_speed = pressure / parameters[L.SURFACES]
    newest_per_mu_speed = newest * fraction * flux_per_mu_speed
    mu, dmu_dspeed, temperature = solve_friction(code, mu_cold, dmu_cold,
                                                 parameters[L.USE_TEMPERATURE] != 0.0,
                                                 base, newest_per_mu_speed * speed,
                                                 newest_per_mu_speed)
    return mu, dmu_dspeed, temperature, mu * flux_per_mu_speed * speed


@jit
def ptv_trial(states, weighted_decay, parameters, position, newest, pressure, speed):
    """One trial of the precise or simplified friction model, fused for speed.

    :func:`heated_window`, :func:`contact_history` and :func:`ptv_friction` in turn: the
    points under the slider at ``position`` [m] on the plate, their committed history, Eq. 7
    with the newest flux (``newest`` = 2 c sqrt(dt) [degC m^2/W]); ``parameters`` from
    :func:`~isolator.compiled.layout.pack_ptv`, ``pressure`` [Pa], ``speed`` [m/s].

    Returns ``(mu, dmu_dspeed, temperature, flux, heated_lo, heated_hi, inside)``: the points
    ``[lo, hi)`` take the flux; ``inside`` is False (nothing else valid) off the monitor line.
    """
    average_over_contact = parameters[L.AVERAGE_OVER_CONTACT] != 0.0
    lo, hi, inside = heated_window(position, parameters[L.FIRST_POINT], parameters[L.SPACING],
                                   int(parameters[L.N_POINTS]),
                                   parameters[L.FLUX_HALF_WIDTH], average_over_contact)
    if not inside:
        return 0.0, 0.0, 0.0, 0.0, 0, 0, False
    if average_over_contact:
        rise = contact_history(states, weighted_decay, lo, hi)
    else:
        rise = contact_history(states, weighted_decay, 0, 1)
    mu, dmu_dspeed, temperature, flux = ptv_friction(rise, hi > lo, parameters, newest,
                                                     pressure, speed)
    return mu, dmu_dspeed, temperature, flux, lo, hi, True


def warm_up() -> None:
    """Compile every kernel now (the first call otherwise pays for it)."""
    states = np.zeros((2, 3))
    vec = np.ones(3)
    contact_history(states, vec, 0, 2)
    advance_states(states, np.ones((2, 3)), 0, 2, 0, 1, 1.0)
    for code in (0, 1):
        solve_friction(code, 0.07, 0.0, True, 20.0, 1.0, 1.0)
        for average in (1.0, 0.0):
            parameters = pack_ptv({
                "first_point": -1.0, "spacing": 1.0, "n_points": 3.0, "flux_half_width": 0.1,
                "average_over_contact": average, "initial_temperature": 20.0,
                "flux_coefficient": 1e-4, "factor_code": code, "reference_pressure": 60e6,
                "rate_parameter": 100.0, "mu_t0": 0.075, "use_pressure": 1.0,
                "use_velocity": 1.0, "use_temperature": 1.0, "surfaces": 2.0})
            ptv_trial(states, vec, parameters, 0.0, 0.01, 60e6, 0.4)
            initial_friction(parameters, 60e6, 0.4)
