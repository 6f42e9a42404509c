"""The DCFPB element, its friction and heating as arrays, for the compiled engine.

:func:`set_trials` and :func:`commit_trials` are ``set_trial`` (with the trial's axial load) and
``commit`` of :class:`isolator.bearing.BearingElement` for every bearing row, operation for
operation, each row's state a row of the ``committed`` / ``trial`` arrays: the isotropic return
map (on a line, the clip of z to +-1, to the bit), the linear / spherical / flat restoring law,
uplift (no load: no force, no heat, the plates cool) and the friction of :mod:`isolator.friction`
through :mod:`isolator.compiled.kernels`: constant (Eq. 8, no heat); PTV without heating (Eq. 7
at the initial temperature); simplified (Eq. 6: the centre point at the distance |u| /
surfaces); precise (Eq. 5: the monitor points under the slider, :mod:`isolator.compiled.plate`;
a line along x in one direction, the grid in two, its frame fixed at the first heated commit).

In one direction the element moves along x (``uy = vy = 0``). Force and tangent are those of
one bearing; the engine multiplies them by ``MULTIPLICITY``. Errors come back as status codes
(``STEP_BELOW_MIN_LAG`` ...) that :func:`isolator.compiled.packing.trial_error` words.
"""

from __future__ import annotations

import math

import numpy as np

from isolator.compiled import layout as L
from isolator.compiled import plate as P
from isolator.compiled.kernels import heated_window, initial_friction, jit_inner, ptv_friction
from isolator.compiled.linking import separately
from isolator.friction import REFERENCE_PRESSURE

# Layout of a row of the ``parameters`` array (one row per bearing; floats).
X, Y, GRAVITY, MULTIPLICITY, YIELD_DISPLACEMENT, RESTORING_LAW, EFFECTIVE_RADIUS = range(7)
CONTACT_AREA, FRICTION_MODEL, CONSTANT_MU, INITIAL_TEMPERATURE, MIN_LAG = range(7, 12)
FLUX_COEFFICIENT, ORIENTATION, N_ACROSS = range(12, 15)  # ORIENTATION NaN: follows the motion
PARAMETERS_SIZE = 15

# Codes of RESTORING_LAW and FRICTION_MODEL.
LINEAR, SPHERICAL, FLAT = 0, 1, 2
CONSTANT, COLD_PTV, CENTRE_PTV, PLATE_PTV = 0, 1, 2, 3

# A bearing state (committed or trial) as BearingState in two directions; then the trial's
# tangents, its pending heat and its frame (the e1 of the plate a trial would fix).
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

# Columns of the ``motion`` array of :func:`set_trials`: each row's trial displacement (x, y)
# [m], velocity (x, y) [m/s] and axial load [N].
MOTION_UX, MOTION_UY, MOTION_VX, MOTION_VY, MOTION_LOAD = range(5)
MOTION_SIZE = 5

# Status codes of a trial (and of a run).
SUCCESS, NOT_CONVERGED, LEFT_MONITOR_LINE, STEP_BELOW_MIN_LAG, BEYOND_RADIUS = range(5)

# The friction and the window's moves, called as code of their own (isolator.compiled.linking;
# calls that LLVM did not inline anyway): the trials and the commit compile without them, and
# a process binds them before it compiles or loads those (structures.compiled.engine).
INITIAL_FRICTION = separately(initial_friction, lambda types: types.UniTuple(types.float64, 3))
PTV_FRICTION = separately(ptv_friction, lambda types: types.UniTuple(types.float64, 4))
MOVE_WINDOW = separately(P.move_window, lambda types: types.none)
REANCHOR_WINDOW = separately(P.reanchor_window, lambda types: types.none)


@jit_inner
def set_trials(time, motion, parameters, ptv, committed, trial, rates, weights, states, stamps,
               marks, pending, accumulators, offsets, cache_keys, cache_values, cache_state,
               scalars, factors, decays, slots, table, windows):
    """BearingElement.set_trial of every bearing row at ``time`` [s]: fills the rows of
    ``trial`` (state, tangents ``KXX`` ... ``CYY`` of one bearing of the row) from ``motion``
    (n_b, MOTION_SIZE; ``MOTION_UX`` ...), ``parameters`` and ``ptv`` (those of
    :class:`isolator.compiled.packing.CompiledBearings`) and the arrays of
    :class:`isolator.compiled.plate.PlateHeat` (``rates`` ... ``windows``). Returns
    ``(status, row)``: ``(SUCCESS, -1)``, or the code of the error the element would raise and
    the row that raised it (the rows after it are not evaluated)."""
    for b in range(motion.shape[0]):
        ux, uy = motion[b, MOTION_UX], motion[b, MOTION_UY]
        vx, vy = motion[b, MOTION_VX], motion[b, MOTION_VY]
        load = motion[b, MOTION_LOAD]
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
        lifted = load <= 0.0  # uplift: no contact, no force, no heat; the plates cool
        if lifted:  # the trial at zero speed and the reference pressure, where no heat enters
            pressure, speed, hint_x, hint_y = REFERENCE_PRESSURE, 0.0, 0.0, 0.0
        else:
            pressure, speed, hint_x, hint_y = load / row[CONTACT_AREA], math.hypot(vx, vy), vx, vy

        # PlateFriction: mu, d mu / d|v|, the temperature and the flux of the trial
        model = np.int64(row[FRICTION_MODEL])
        if model == CONSTANT:
            mu, dmu_dspeed, flux = row[CONSTANT_MU], 0.0, 0.0
            temperature = row[INITIAL_TEMPERATURE]
        elif model == COLD_PTV or dt <= 0.0:
            mu, dmu_dspeed, temperature = INITIAL_FRICTION(constants, pressure, speed)
            flux = mu * pressure * speed / constants[L.SURFACES]
        else:
            if dt == table[P.PREPARED_STEP]:
                slot = np.int64(table[P.SLOT])
            else:
                slot = P.prepare_step(dt, row[FLUX_COEFFICIENT], row[MIN_LAG], rates, weights,
                                      factors, decays, slots, table)
            if slot < 0:
                t[PENDING_DT] = dt
                t[UX], t[UY] = ux, uy
                return STEP_BELOW_MIN_LAG, b
            surfaces = constants[L.SURFACES]
            sx, sy = ux / surfaces, uy / surfaces  # the slider on each plate
            window, held = windows[b, P.TRIAL_WINDOW], windows[b, P.HELD]
            grid = model == PLATE_PTV  # a value, not a literal: one specialisation of kernels
            if not grid:  # the centre point: ptv_trial on the distance from the centre
                lo, hi, _ = heated_window(math.hypot(ux, uy) / surfaces,
                                          constants[L.FIRST_POINT], constants[L.SPACING],
                                          np.int64(constants[L.N_POINTS]),
                                          constants[L.FLUX_HALF_WIDTH], grid)
                rise = 0.0
                for k in range(decays.shape[1]):
                    rise += states[b, 0, k] * decays[slot, k]
                window[0], window[1] = lo, hi
                heated = hi > lo
            else:  # the monitor points: GridHeating.trial (a line: one row across)
                plate = scalars[b]
                if plate[P.FRAME_FIXED] != 0.0:
                    e1x, e1y = plate[P.E1X], plate[P.E1Y]
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
                half_width = constants[L.FLUX_HALF_WIDTH]
                n_along, n_across = np.int64(constants[L.N_POINTS]), np.int64(row[N_ACROSS])
                i_lo, i_hi, inside = heated_window(e1x * sx + e1y * sy, first, spacing, n_along,
                                                   half_width, grid)
                k_lo, k_hi = 0, 1
                if n_across > 1:
                    k_lo, k_hi, inside_k = heated_window(-e1y * sx + e1x * sy, first, spacing,
                                                         n_across, half_width, grid)
                    inside = inside and inside_k
                if not inside:
                    t[UX], t[UY] = ux, uy
                    return LEFT_MONITOR_LINE, b
                window[0], window[1], window[2], window[3] = i_lo, i_hi, k_lo, k_hi
                if plate[P.FRAME_FIXED] == 0.0:
                    rise = 0.0  # nothing stored before the first heated commit
                elif (i_lo == held[0] and i_hi == held[1] and k_lo == held[2]
                      and k_hi == held[3] and plate[P.RISE_VALID] != 0.0
                      and plate[P.RISE_STEP] == dt):
                    rise = plate[P.RISE]  # Newton's trials of a step mostly share it
                else:  # the trial's window becomes the one held as a group
                    if i_lo != held[0] or i_hi != held[1] or k_lo != held[2] or k_hi != held[3]:
                        MOVE_WINDOW(b, n_across, held, window, plate[P.HEAT_TIME], rates,
                                      states[b], stamps[b], accumulators[b], offsets[b],
                                      cache_keys, cache_values, cache_state, marks[b], pending[b])
                        held[0], held[1], held[2], held[3] = i_lo, i_hi, k_lo, k_hi
                    points = (i_hi - i_lo if i_hi > i_lo else 0) * (k_hi - k_lo)
                    rise = P.window_history(accumulators[b], offsets[b], decays[slot], points)
                    plate[P.RISE], plate[P.RISE_VALID], plate[P.RISE_STEP] = rise, 1.0, dt
                heated = i_hi > i_lo and k_hi > k_lo
            mu, dmu_dspeed, temperature, flux = PTV_FRICTION(
                rise, heated, constants, slots[slot, P.SLOT_NEWEST], pressure, speed)
            t[PENDING_DT], t[PENDING] = dt, 1.0

        n = load
        rx = ry = kxx = kxy = kyx = kyy = 0.0
        ex = ey = 0.0
        if lifted:
            mu, dmu_dspeed, flux, n = 0.0, 0.0, 0.0, 0.0
        else:
            if speed > 0.0:
                ex, ey = vx / speed, vy / speed
            law = np.int64(row[RESTORING_LAW])
            radius = row[EFFECTIVE_RADIUS]
            if law == SPHERICAL:
                squared = radius**2 - (ux * ux + uy * uy)
                if not squared > 0.0:
                    t[UX], t[UY] = ux, uy
                    t[PENDING] = 0.0
                    return BEYOND_RADIUS, b
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
    return SUCCESS, -1


@jit_inner
def commit_trials(parameters, committed, trial, rates, weights, states, stamps, marks, pending,
                  accumulators, offsets, cache_keys, cache_values, cache_state, scalars,
                  factors, decays, slots, table, windows):
    """BearingElement.commit of every bearing row: the trial becomes the committed state
    and its heat enters the plate's history (the arrays as for :func:`set_trials`)."""
    for b in range(trial.shape[0]):
        t = trial[b]
        if t[PENDING] != 0.0:
            row = parameters[b]
            dt, flux = t[PENDING_DT], t[HEAT_FLUX]
            if dt == table[P.PREPARED_STEP]:
                slot = np.int64(table[P.SLOT])
            else:
                slot = P.prepare_step(dt, row[FLUX_COEFFICIENT], row[MIN_LAG], rates, weights,
                                      factors, decays, slots, table)
            step = factors[slot]
            window, held = windows[b, P.TRIAL_WINDOW], windows[b, P.HELD]
            if np.int64(row[FRICTION_MODEL]) == CENTRE_PTV:  # advance_states on one point
                heated = window[1] > window[0] and flux != 0.0
                for k in range(step.shape[1]):
                    if heated:
                        states[b, 0, k] = states[b, 0, k] * step[0, k] + flux * step[1, k]
                    else:
                        states[b, 0, k] *= step[0, k]
            else:  # the monitor points: GridHeating.commit on the window held as a group
                n_across = np.int64(row[N_ACROSS])
                plate = scalars[b]
                if flux != 0.0 and window[1] > window[0] and window[3] > window[2]:
                    if plate[P.FRAME_FIXED] == 0.0:  # the first heated commit fixes the frame
                        plate[P.FRAME_FIXED], plate[P.E1X], plate[P.E1Y] = 1.0, t[AXIS_X], \
                            t[AXIS_Y]
                    if (window[0] != held[0] or window[1] != held[1] or window[2] != held[2]
                            or window[3] != held[3]):
                        MOVE_WINDOW(b, n_across, held, window, plate[P.HEAT_TIME], rates,
                                      states[b], stamps[b], accumulators[b], offsets[b],
                                      cache_keys, cache_values, cache_state, marks[b], pending[b])
                        held[0], held[1], held[2], held[3] = window[0], window[1], window[2], \
                            window[3]
                    # the points waiting to be stored take the number of this heated commit
                    plate[P.HEAT_COMMITS] += 1.0
                    number = np.int64(plate[P.HEAT_COMMITS])
                    waiting = pending[b]
                    for p in range(1, waiting[0] + 1):
                        j = waiting[p]
                        i, k = j // n_across, j % n_across
                        inside = window[0] <= i < window[1] and window[2] <= k < window[3]
                        marks[b, j] = number if inside else P.UNTOUCHED
                    waiting[0] = 0
                else:
                    flux = 0.0
                P.advance_window(accumulators[b], offsets[b], step, flux)
                plate[P.HEAT_TIME] += dt
                plate[P.RISE_VALID] = 0.0
                if plate[P.FRAME_FIXED] != 0.0:
                    plate[P.ANCHORED_AGO] += 1.0
                    if plate[P.ANCHORED_AGO] >= P.REANCHOR_EVERY:
                        REANCHOR_WINDOW(b, n_across, held, plate[P.HEAT_TIME], rates,
                                          states[b], stamps[b], offsets[b], cache_keys,
                                          cache_values, cache_state)
                        plate[P.ANCHORED_AGO] = 0.0
        t[PENDING] = 0.0
        c = committed[b]
        for i in range(AXIAL_LOAD + 1):
            c[i] = t[i]
