"""An independent, deliberately plain implementation of the SSB paper's friction models.

Nishimoto et al., "SSB part 2: friction models" (``shared/reference/ssb-part2-friction-models``),
Section 2 (Eq. 1-8) and Section 3.1 (Eq. 9-11), written from the paper alone for a
cross-check of the package. It imports nothing from ``isolator``, ``structures`` or ``dcfpb``:
its value is that it shares no code with them. Speed and elegance are not goals; being easy
to check against the paper is.

Conventions (SI at every argument; the paper's N/mm^2 and mm/s only inside the factors):

- Eq. 1-3: gamma = 2.03 sigma^-0.19 + 0.068 (sigma in N/mm^2), alpha = 1 - 0.55 exp(-0.019 v)
  (|v| in mm/s), beta = 1.13 exp(-0.007 T) (T in degC).
- Eq. 7: mu = mu_t0 gamma(p) alpha(v) beta(T), mu_t0 = 0.075 (precise and simplified models).
- Eq. 8: mu_c = mu_0 gamma(sigma_d) alpha(v_d) beta(T0), mu_0 = 0.041 (300 mm slider).
- Bearing: p = N / (pi r^2), F = N u / R_eff + mu N z, z from an elastic-plastic return map
  with yield displacement u_y (z = 0 at u = 0 at the start).
- Step i runs from t_{i-1} to t_i and uses the end-of-step values u_i, v_i; sample 0 records
  F = 0 (mu = 0 there: no step has been taken).
- Eq. 4 for a piecewise-constant flux, summed exactly over the whole history every step:
  dT(t_n) = c sum_j q_j 2 (sqrt(t_n - t_{j-1}) - sqrt(t_n - t_j)), c = sqrt(D) / (k sqrt(pi)).
- Eq. 5/6: a DCFPB's slider is at u/2 on each plate and each plate takes q = mu p |v| / 2.
  Precise model: monitor points every 5 mm; a point is heated when within sqrt(pi) r / 2 of
  the slider centre and the contact temperature is the mean over those same points.
  Simplified model: one point at the plate centre, heated when |u/2| <= lambda r; its
  temperature is the contact temperature.
- The newest interval's flux depends on mu_i, which depends on T_i: mu_i is found by a plain
  fixed-point iteration mu <- mu_t0 gamma alpha beta(T_hist + 2 c sqrt(dt) q(mu)).
"""

from __future__ import annotations

import math

import numpy as np

DIFFUSIVITY = 4.07e-6  # D [m^2/s] (4.07 mm^2/s, JSME data book)
CONDUCTIVITY = 16.0  # k [W/(m degC)] (0.016 W/(mm degC))
T0 = 20.0  # initial temperature [degC]
C = math.sqrt(DIFFUSIVITY) / (CONDUCTIVITY * math.sqrt(math.pi))  # Eq. 4 coefficient

MU_T0 = 0.075  # Eq. 7
MU0_300 = 0.041  # Eq. 8, 300 mm slider
YIELD_DISPLACEMENT = 5.0e-4  # u_y [m]
SPACING = 0.005  # monitor point interval of the precise model [m]
LAMBDA = 0.5  # refinement factor of the simplified model
# The heating windows are closed (Eq. 5/6: delta <= ...). A protocol can put samples exactly on
# the edge (the test sine with dt = T/852 has |u/2| = 0.5 r at every 30 degrees of phase), where
# sin() rounding alone would decide; a slack of 1e-12 m keeps such exact ties inside.
EDGE_SLACK = 1.0e-12  # [m]

MODELS = ("precise", "simplified", "constant")


# --- Eq. 1-3 -------------------------------------------------------------------------------


def gamma(pressure_pa: float) -> float:
    """Eq. 1, pressure in Pa (converted to N/mm^2)."""
    sigma = pressure_pa / 1.0e6
    return 2.03 * sigma**-0.19 + 0.068


def alpha(velocity_m_s: float) -> float:
    """Eq. 2, velocity in m/s (converted to mm/s, magnitude)."""
    v_mm = abs(velocity_m_s) * 1000.0
    return 1.0 - 0.55 * math.exp(-0.019 * v_mm)


def beta(temperature: float) -> float:
    """Eq. 3, temperature in degC."""
    return 1.13 * math.exp(-0.007 * temperature)


# --- imposed history -----------------------------------------------------------------------


def sine_protocol(amplitude: float, period: float, cycles: int, dt: float):
    """Samples t_i = i dt, u = A sin(2 pi t / T), v = A (2 pi / T) cos(2 pi t / T).

    Returns (t, u, v, samples_per_cycle); dt must divide the period.
    """
    per_cycle = round(period / dt)
    assert abs(per_cycle * dt - period) < 1e-9 * period, "dt must divide the period"
    n = per_cycle * cycles
    t = np.arange(n + 1) * dt
    omega = 2.0 * math.pi / period
    u = amplitude * np.sin(omega * t)
    v = amplitude * omega * np.cos(omega * t)
    return t, u, v, per_cycle


# --- Eq. 4: exact convolution weights -------------------------------------------------------


def history_weights(t: np.ndarray, n: int) -> np.ndarray:
    """Weights of intervals 1..n-1 at time t_n: 2 (sqrt(t_n - t_{j-1}) - sqrt(t_n - t_j)).

    Written as 2 (t_j - t_{j-1}) / (sqrt(t_n - t_{j-1}) + sqrt(t_n - t_j)) (the same number,
    without cancellation). Interval j is [t_{j-1}, t_j]; element j-1 of the result is its weight.
    """
    roots = np.sqrt(t[n] - t[:n])  # sqrt(t_n - t_k), k = 0..n-1
    return 2.0 * np.diff(t[:n]) / (roots[:-1] + roots[1:])


# --- the three models -----------------------------------------------------------------------


def simulate(
    model: str,
    t: np.ndarray,
    u: np.ndarray,
    v: np.ndarray,
    *,
    slider_diameter: float = 0.3,
    pressure: float = 60.0e6,
    effective_radius: float = 4.5,
    design_velocity: float | None = None,
    mu0: float = MU0_300,
    mu_t0: float = MU_T0,
    refinement: float = LAMBDA,
    yield_displacement: float = YIELD_DISPLACEMENT,
    tolerance: float = 1.0e-15,
) -> dict[str, np.ndarray]:
    """Run one of the paper's models on an imposed history (t, u, v).

    Returns a dict of arrays (one value per sample): force [N], mu [-], temperature [degC]
    (contact temperature; T0 for the constant model), heat_flux [W/m^2] (mu p |v| / 2, the
    flux under the slider on each plate; 0 for the constant model), z [-]. Also the scalar
    ``axial_load`` [N].
    """
    assert model in MODELS, model
    t, u, v = (np.asarray(a, dtype=float) for a in (t, u, v))
    n_samples = t.size
    r = 0.5 * slider_diameter
    axial_load = pressure * math.pi * r * r  # p = N / (pi r^2)

    force = np.zeros(n_samples)
    mu = np.zeros(n_samples)
    temperature = np.full(n_samples, T0)
    heat_flux = np.zeros(n_samples)
    z_hist = np.zeros(n_samples)

    if model == "precise":
        half_width = 0.5 * math.sqrt(math.pi) * r  # half side of the equal-area square
        m = math.ceil((np.max(np.abs(u)) / 2.0 + half_width) / SPACING) + 1
        points = SPACING * np.arange(-m, m + 1)
    elif model == "simplified":
        half_width = refinement * r
        points = np.zeros(1)
    else:
        points = np.zeros(0)
        v_d = design_velocity
        assert v_d is not None, "the constant model needs design_velocity"
        mu_constant = mu0 * gamma(pressure) * alpha(v_d) * beta(T0)  # Eq. 8

    # fluxes[p, j - 1]: flux into point p during interval j = 1..n (piecewise constant).
    fluxes = np.zeros((points.size, max(n_samples - 1, 0)))

    z = 0.0
    for i in range(1, n_samples):
        dt = t[i] - t[i - 1]
        speed = abs(v[i])
        if model == "constant":
            mu_i = mu_constant
            t_contact = T0
            q = 0.0
        else:
            mu_cold = mu_t0 * gamma(pressure) * alpha(v[i])  # Eq. 7 without beta
            flux_per_mu = pressure * speed / 2.0  # q = mu p |v| / 2 on each plate (Eq. 5)
            newest = 2.0 * C * math.sqrt(dt)  # the newest interval's weight times c
            if model == "precise":
                window = np.abs(points - u[i] / 2.0) <= half_width + EDGE_SLACK
                assert window.sum() > 0 and not window[0] and not window[-1]
            else:
                window = np.array([abs(u[i] / 2.0) <= half_width + EDGE_SLACK])
            if model == "precise":
                rows = np.flatnonzero(window)
                if i > 1:
                    w = history_weights(t, i)
                    hist = fluxes[rows[0]:rows[-1] + 1, : i - 1] @ w
                    t_hist = T0 + C * float(np.mean(hist))
                else:
                    t_hist = T0
                heated_fraction = 1.0  # every averaged point takes the newest flux
            else:
                if i > 1:
                    w = history_weights(t, i)
                    t_hist = T0 + C * float(fluxes[0, : i - 1] @ w)
                else:
                    t_hist = T0
                heated_fraction = 1.0 if window[0] else 0.0
            slope = newest * flux_per_mu * heated_fraction  # d T_contact / d mu
            mu_i = mu_cold * beta(t_hist)
            for _ in range(200):  # fixed point: a contraction (|d/dmu| ~ 0.007 mu slope << 1)
                new = mu_cold * beta(t_hist + slope * mu_i)
                done = abs(new - mu_i) <= tolerance * new
                mu_i = new
                if done:
                    break
            else:
                raise RuntimeError(f"fixed point did not converge at step {i}")
            t_contact = t_hist + slope * mu_i
            q = mu_i * flux_per_mu
            fluxes[window, i - 1] = q
        # Elastic-plastic return map for z.
        z = z + (u[i] - u[i - 1]) / yield_displacement
        z = min(1.0, max(-1.0, z))
        force[i] = axial_load * u[i] / effective_radius + mu_i * axial_load * z
        mu[i] = mu_i
        temperature[i] = t_contact
        heat_flux[i] = q
        z_hist[i] = z
    return {
        "force": force, "mu": mu, "temperature": temperature, "heat_flux": heat_flux,
        "z": z_hist, "axial_load": axial_load,
    }


# --- Section 3.1: per-cycle characteristics -------------------------------------------------


def cycle_characteristics(u: np.ndarray, force: np.ndarray, samples_per_cycle: int):
    """Fmax, Fmin, Dmax, Dmin, EDC, Keff (Eq. 10), beta_eff (Eq. 11) for each full cycle.

    Cycle k (1-based) is samples (k-1) P .. k P inclusive, P = ``samples_per_cycle``.
    EDC is the loop integral of F du by the trapezoid rule.
    """
    out = []
    n_cycles = (u.size - 1) // samples_per_cycle
    for k in range(n_cycles):
        s = slice(k * samples_per_cycle, (k + 1) * samples_per_cycle + 1)
        uu, ff = u[s], force[s]
        f_max, f_min = float(ff.max()), float(ff.min())
        d_max, d_min = float(uu.max()), float(uu.min())
        edc = float(np.sum(0.5 * (ff[1:] + ff[:-1]) * np.diff(uu)))
        span = abs(d_max) + abs(d_min)
        k_eff = (abs(f_max) + abs(f_min)) / span  # Eq. 10
        beta_eff = 2.0 / math.pi * edc / (k_eff * span**2)  # Eq. 11
        out.append({
            "cycle": k + 1, "Fmax": f_max, "Fmin": f_min, "Dmax": d_max, "Dmin": d_min,
            "EDC": edc, "Keff": k_eff, "beta_eff": beta_eff,
        })
    return out
