"""The DCFPB element, its friction and heating as arrays, for the compiled engine.

:func:`element_trial` and :func:`element_commit` are ``BidirectionalElement.set_trial`` (with
the trial's axial load) and ``commit`` of :mod:`isolator.bidirectional.element` for bearing
``b``, its state a row of the ``committed`` / ``trial`` arrays (``TIME`` ... ``AXIAL_LOAD``,
then the trial's tangents, its pending heat and its frame), operation for operation: the
isotropic return map (on a line, the clip of the planar element's z to +-1, to the bit), the
linear / spherical / flat restoring law, uplift (no load: no force, no heat, the plates cool),
and the friction of :mod:`isolator.friction` and :mod:`isolator.bidirectional.friction`
through the kernels of :mod:`isolator.compiled.kernels` (``cold_friction``,
``solve_friction``, ``heated_window``, ``ptv_friction``; the step factors of
:func:`isolator.heating.step_factors`, exact for every step size):

- constant (Eq. 8): mu_c, no heat;
- PTV without heating: Eq. 7 at the initial temperature, with the trial's pressure;
- simplified (Eq. 6): the centre point at the distance |u| / surfaces, its history updated as
  ``advance_states`` does, bit for bit;
- precise (Eq. 5): the monitor points under the slider held as a group
  (:mod:`isolator.compiled.plate`): the planar element's monitor line (one row across, e1
  along x) or the bidirectional element's grid (its frame fixed by the motion at the first
  heated commit, as the reference's).

The planar element is this one moving along x with its constant axial load: the building's
engine gives it ``uy = vy = 0``. A bearing row may stand for several identical bearings
(``MULTIPLICITY``): the engine multiplies its force and tangent, the element does not.
Errors the element would raise come back as status codes, with what
:func:`isolator.compiled.packing.trial_error` needs to word them (``STEP_BELOW_MIN_LAG``,
``LEFT_MONITOR_LINE``, ``BEYOND_RADIUS``). The Python side (packing a bearing into these
arrays, the errors' words, the plate field) is :mod:`isolator.compiled.packing`.
"""

from __future__ import annotations

import math

from isolator.compiled import layout as L
from isolator.compiled import plate as P
from isolator.compiled.kernels import (
    cold_friction,
    heated_window,
    jit,
    ptv_friction,
    solve_friction,
)
from isolator.friction import REFERENCE_PRESSURE

# Layout of a row of the ``parameters`` array (one row per bearing; floats).
X, Y, GRAVITY, MULTIPLICITY, YIELD_DISPLACEMENT, RESTORING_LAW, EFFECTIVE_RADIUS = range(7)
CONTACT_AREA, FRICTION_MODEL, CONSTANT_MU, INITIAL_TEMPERATURE, MIN_LAG = range(7, 12)
FLUX_COEFFICIENT, ORIENTATION, N_ACROSS = range(12, 15)  # ORIENTATION NaN: follows the motion
PARAMETERS_SIZE = 15

# Codes of RESTORING_LAW and FRICTION_MODEL.
LINEAR, SPHERICAL, FLAT = 0, 1, 2
CONSTANT, COLD_PTV, CENTRE_PTV, PLATE_PTV = 0, 1, 2, 3

# A bearing state (committed or trial) as PlanarState; then the trial's tangents, its pending
# heat and its frame (the e1 of the plate a trial would fix).
TIME, UX, UY, VX, VY, FX, FY, FFX, FFY, ZX, ZY, MU, TEMPERATURE, HEAT_FLUX, AXIAL_LOAD = range(15)
KXX, KXY, KYX, KYY, CXX, CXY, CYX, CYY = range(15, 23)
PENDING_DT, PENDING, AXIS_X, AXIS_Y = range(23, 27)
STATE_SIZE = 27

# Columns of the engine's per-step record of every bearing (what results need).
RECORD_COLUMNS = (UX, UY, FX, FY, FFX, FFY, MU, TEMPERATURE, HEAT_FLUX, AXIAL_LOAD)
RECORD_FIELDS = (("displacement", (0, 1)), ("force", (2, 3)), ("friction_force", (4, 5)),
                 ("mu", (6,)), ("temperature", (7,)), ("heat_flux", (8,)),
                 ("axial_load", (9,)))
"""The recorded fields: name and their columns of the record (x, y for the vectors) [SI]."""
RECORD_SIZE = 10

# Status codes of a trial (and of a run).
SUCCESS, NOT_CONVERGED, LEFT_MONITOR_LINE, STEP_BELOW_MIN_LAG, BEYOND_RADIUS = range(5)


@jit
def element_trial(b, ux, uy, vx, vy, time, load, parameters, ptv, committed, trial, heat):
    """BidirectionalElement.set_trial of bearing ``b`` at the axial ``load`` [N]: fills the
    row ``trial[b]`` (state, tangents ``KXX`` ... ``CYY`` of one bearing); returns the status.

    ``parameters`` and ``ptv`` (one row per bearing) are :mod:`isolator.compiled.packing`'s,
    ``heat`` the tuple of :func:`isolator.compiled.plate.new_plate_heating`.
    """
    row, c, t = parameters[b], committed[b], trial[b]
    constants = ptv[b]
    dt = time - c[TIME]
    yield_displacement = row[YIELD_DISPLACEMENT]
    px = c[ZX] + (ux - c[UX]) / yield_displacement  # isotropic_return_map
    py = c[ZY] + (uy - c[UY]) / yield_displacement
    size = math.hypot(px, py)
    if size >= 1.0:
        zx, zy = px / size, py / size
        scale = yield_displacement * size
        dxx, dxy = (1.0 - zx * zx) / scale, (0.0 - zx * zy) / scale
        dyx, dyy = (0.0 - zy * zx) / scale, (1.0 - zy * zy) / scale
    else:
        zx, zy = px, py
        dxx, dxy, dyx, dyy = 1.0 / yield_displacement, 0.0, 0.0, 1.0 / yield_displacement
    t[PENDING] = 0.0
    lifted = load <= 0.0  # uplift: no contact, no force, no heat; the plates cool (``lifted``)
    if lifted:  # the trial at zero speed and the reference pressure, where no heat enters
        pressure, speed, hint_x, hint_y = REFERENCE_PRESSURE, 0.0, 0.0, 0.0
    else:
        pressure, speed, hint_x, hint_y = load / row[CONTACT_AREA], math.hypot(vx, vy), vx, vy

    # PlateFriction: mu, d mu / d|v|, the temperature and the flux of the trial
    model = int(row[FRICTION_MODEL])
    if model == CONSTANT:
        mu, dmu_dspeed, temperature, flux = row[CONSTANT_MU], 0.0, row[INITIAL_TEMPERATURE], 0.0
    elif model == COLD_PTV or dt <= 0.0:
        code = int(constants[L.FACTOR_CODE])
        mu_cold, dmu_cold = cold_friction(code, constants[L.REFERENCE_PRESSURE],
                                          constants[L.RATE_PARAMETER], constants[L.MU_T0],
                                          constants[L.USE_PRESSURE] != 0.0,
                                          constants[L.USE_VELOCITY] != 0.0, pressure, speed)
        mu, dmu_dspeed, temperature = solve_friction(code, mu_cold, dmu_cold,
                                                     constants[L.USE_TEMPERATURE] != 0.0,
                                                     constants[L.INITIAL_TEMPERATURE], 0.0, 0.0)
        flux = mu * pressure * speed / constants[L.SURFACES]
    else:
        slot = P.prepare_step(dt, row[FLUX_COEFFICIENT], row[MIN_LAG], heat)
        if slot < 0:
            t[PENDING_DT] = dt
            t[UX], t[UY] = ux, uy
            return STEP_BELOW_MIN_LAG
        surfaces = constants[L.SURFACES]
        sx, sy = ux / surfaces, uy / surfaces  # the slider on each plate
        window = heat[P.WINDOWS][b, P.TRIAL_WINDOW]
        if model == CENTRE_PTV:  # ptv_trial on the distance from the centre
            lo, hi, _ = heated_window(math.hypot(ux, uy) / surfaces, constants[L.FIRST_POINT],
                                      constants[L.SPACING], int(constants[L.N_POINTS]),
                                      constants[L.FLUX_HALF_WIDTH], False)
            states, decays = heat[P.STATES], heat[P.DECAYS]
            rise = 0.0
            for k in range(decays.shape[1]):
                rise += states[b, 0, k] * decays[slot, k]
            window[0], window[1] = lo, hi
            heated = hi > lo
        else:  # the monitor points: GridHeating.trial (a line: one row across)
            scalars = heat[P.SCALARS][b]
            if scalars[P.FRAME_FIXED] != 0.0:
                e1x, e1y = scalars[P.E1X], scalars[P.E1Y]
            elif not math.isnan(row[ORIENTATION]):
                e1x, e1y = math.cos(row[ORIENTATION]), math.sin(row[ORIENTATION])
            else:  # plate_frame: along the position, else the velocity, else x
                e1x, e1y = 1.0, 0.0
                length = math.hypot(sx, sy)
                if length > 0.0:
                    e1x, e1y = sx / length, sy / length
                else:
                    length = math.hypot(hint_x, hint_y)
                    if length > 0.0:
                        e1x, e1y = hint_x / length, hint_y / length
            t[AXIS_X], t[AXIS_Y] = e1x, e1y
            first, spacing = constants[L.FIRST_POINT], constants[L.SPACING]
            half_width, n_along = constants[L.FLUX_HALF_WIDTH], int(constants[L.N_POINTS])
            n_across = int(row[N_ACROSS])
            i_lo, i_hi, inside = heated_window(e1x * sx + e1y * sy, first, spacing, n_along,
                                               half_width, True)
            k_lo, k_hi = 0, 1
            if n_across > 1:
                k_lo, k_hi, inside_k = heated_window(-e1y * sx + e1x * sy, first, spacing,
                                                     n_across, half_width, True)
                inside = inside and inside_k
            if not inside:
                t[UX], t[UY] = ux, uy
                return LEFT_MONITOR_LINE
            rise = P.window_rise(b, n_across, i_lo, i_hi, k_lo, k_hi, dt, slot, heat)
            heated = i_hi > i_lo and k_hi > k_lo
        mu, dmu_dspeed, temperature, flux = ptv_friction(
            rise, heated, constants, heat[P.SLOTS][slot, P.SLOT_NEWEST], pressure, speed)
        t[PENDING_DT], t[PENDING] = dt, 1.0

    n = load
    rx = ry = kxx = kxy = kyx = kyy = 0.0
    ex = ey = 0.0
    if lifted:
        mu, dmu_dspeed, flux, n = 0.0, 0.0, 0.0, 0.0
    else:
        if speed > 0.0:
            ex, ey = vx / speed, vy / speed
        law = int(row[RESTORING_LAW])
        radius = row[EFFECTIVE_RADIUS]
        if law == SPHERICAL:
            squared = radius**2 - (ux * ux + uy * uy)
            if not squared > 0.0:
                t[UX], t[UY] = ux, uy
                t[PENDING] = 0.0
                return BEYOND_RADIUS
            root = math.sqrt(squared)
            cube = root**3
            rx, ry = n * ux / root, n * uy / root
            kxx, kxy = n * (1.0 / root + ux * ux / cube), n * (0.0 / root + ux * uy / cube)
            kyx, kyy = n * (0.0 / root + uy * ux / cube), n * (1.0 / root + uy * uy / cube)
        elif law == LINEAR:
            rx, ry = n * ux / radius, n * uy / radius
            kxx = kyy = n / radius
    mu_n = mu * n
    ffx, ffy = mu_n * zx, mu_n * zy
    t[TIME], t[UX], t[UY], t[VX], t[VY] = time, ux, uy, vx, vy
    t[FX], t[FY], t[FFX], t[FFY], t[ZX], t[ZY] = rx + ffx, ry + ffy, ffx, ffy, zx, zy
    t[MU], t[TEMPERATURE], t[HEAT_FLUX], t[AXIAL_LOAD] = mu, temperature, flux, n
    t[KXX], t[KXY] = kxx + mu_n * dxx, kxy + mu_n * dxy
    t[KYX], t[KYY] = kyx + mu_n * dyx, kyy + mu_n * dyy
    dvx, dvy = dmu_dspeed * ex, dmu_dspeed * ey
    t[CXX], t[CXY], t[CYX], t[CYY] = n * (zx * dvx), n * (zx * dvy), n * (zy * dvx), \
        n * (zy * dvy)
    return SUCCESS


@jit
def element_commit(b, parameters, committed, trial, heat):
    """BidirectionalElement.commit of bearing ``b``: the trial becomes the committed state and
    its heat enters the plate's history."""
    t = trial[b]
    if t[PENDING] != 0.0:
        row = parameters[b]
        dt, flux = t[PENDING_DT], t[HEAT_FLUX]
        slot = P.prepare_step(dt, row[FLUX_COEFFICIENT], row[MIN_LAG], heat)
        if int(row[FRICTION_MODEL]) == CENTRE_PTV:  # advance_states on one point
            step, states = heat[P.FACTORS][slot], heat[P.STATES]
            window = heat[P.WINDOWS][b, P.TRIAL_WINDOW]
            heated = window[1] > window[0] and flux != 0.0
            for k in range(step.shape[1]):
                if heated:
                    states[b, 0, k] = states[b, 0, k] * step[0, k] + flux * step[1, k]
                else:
                    states[b, 0, k] *= step[0, k]
        else:
            P.commit_window(b, int(row[N_ACROSS]), dt, slot, flux, t[AXIS_X], t[AXIS_Y], heat)
    t[PENDING] = 0.0
    c = committed[b]
    for i in range(AXIAL_LOAD + 1):
        c[i] = t[i]
