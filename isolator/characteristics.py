"""Per-cycle force-deflection characteristics of a bearing test (paper Section 3.1, Fig. 7,
Eq. 9-11, after ASCE/SEI 7-16).

Each complete cycle of a displacement [m] and force [N] history gets Fmax, Fmin, the post-yield
stiffnesses Kru, Krl (least squares) and Kra (Eq. 9), the energy dissipated per cycle EDC (loop
integral), Keff (Eq. 10) and beta_eff (Eq. 11). Cycles are found from the displacement alone
(:func:`find_cycles`); each loop is closed on the mid-level, so EDC does not change when a
constant is added to the force and the EDCs of consecutive cycles add up.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from itertools import pairwise

import numpy as np

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_array, check_choice, check_real

_AT_MID_LEVEL = 1e-9  # |u0 - mid| below this fraction of the largest excursion: "at" the level


@dataclass(frozen=True)
class CycleCharacteristics:
    """Force-deflection characteristics of one cycle (paper Fig. 7, Eq. 9-11).

    Attributes
    ----------
    cycle : int
        Number of the complete cycle in the history, from 1.
    start, stop : int
        Samples ``[start, stop)`` of the cycle (:func:`find_cycles`).
    Dmax, Dmin, Fmax, Fmin : float
        Largest and smallest displacement [m] and force [N] of the cycle.
    Kru, Krl : float
        Upper and lower post-yield stiffness, the least-squares slopes of the branches moving in
        +u and -u [N/m].
    Kra : float
        Average post-yield stiffness ``(|Kru| + |Krl|) / 2`` (Eq. 9) [N/m].
    EDC : float
        Energy dissipated per cycle, the loop integral of F du [J].
    Keff, beta_eff : float
        Effective stiffness (Eq. 10) [N/m] and effective damping (Eq. 11) [-], NaN when the force
        is constant over the cycle.
    start_time, stop_time : float or None
        Times of the two upward crossings that bound the cycle [s], when a time was given.
    """

    cycle: int
    start: int
    stop: int
    Dmax: float
    Dmin: float
    Fmax: float
    Fmin: float
    Kru: float
    Krl: float
    Kra: float
    EDC: float
    Keff: float
    beta_eff: float
    start_time: float | None = None
    stop_time: float | None = None

    def to_dict(self) -> dict[str, float]:
        """The characteristics under the paper's names (cycle, Fmax, ..., Dmin)."""
        keys = ("cycle", "Fmax", "Fmin", "Kru", "Krl", "Kra", "EDC", "Keff", "beta_eff")
        values = asdict(self)
        return {key: values[key] for key in (*keys, "Dmax", "Dmin")}


def _mid_level(displacement: np.ndarray, mid_level: float | str, owner: str) -> float:
    if isinstance(mid_level, str):
        check_choice(mid_level, "mid_level", owner, ("median",))
        return float(np.median(displacement))
    return check_real(mid_level, "mid_level", owner)


def _upward_crossings(excursion: np.ndarray, at_level: float) -> np.ndarray:
    """Indices i with e[i-1] < 0 <= e[i]; 0 first when the history starts on the level."""
    up = np.flatnonzero((excursion[:-1] < 0.0) & (excursion[1:] >= 0.0)) + 1
    if abs(excursion[0]) <= at_level:
        up = np.concatenate([[0], up])
    return up


def _find_cycles(
    excursion: np.ndarray, crossing_band: float, min_excursion: float
) -> list[tuple[int, int]]:
    scale = float(np.max(np.abs(excursion)))
    if scale == 0.0:
        return []
    band, at_level = crossing_band * scale, _AT_MID_LEVEL * scale
    side = np.where(excursion > band, 1, np.where(excursion < -band, -1, 0))
    where = np.flatnonzero(side)
    sides = side[where]
    if excursion[0] <= at_level:  # starts on or below the level: armed for an upward crossing
        where, sides = np.concatenate([[0], where]), np.concatenate([[-1], sides])
    # A boundary: the signal leaves the band upward after it last left it downward; the
    # cycle starts at the last upward crossing of the level before that sample.
    rising = where[1:][(sides[1:] == 1) & (sides[:-1] == -1)]
    up = _upward_crossings(excursion, at_level)
    bounds = list(up[np.searchsorted(up, rising, side="right") - 1])
    if abs(excursion[-1]) <= at_level and sides.size and sides[-1] == -1:
        # Ends on the level coming up from below: the last crossing closes the last cycle.
        after = up[up > where[-1]]
        bounds.append(after[-1] if after.size else excursion.size - 1)
    cycles = []
    for start, stop in pairwise(bounds):
        positive = float(np.max(excursion[start:stop]))
        negative = -float(np.min(excursion[start:stop]))
        if min(positive, negative) >= min_excursion * max(positive, negative):
            cycles.append((int(start), int(stop)))
    return cycles


def find_cycles(
    displacement: object,
    *,
    mid_level: float | str = 0.0,
    crossing_band: float = 0.05,
    min_excursion: float = 0.3,
) -> list[tuple[int, int]]:
    """Complete displacement cycles, each from one upward crossing of the mid-level to the next.

    An upward crossing at i means ``u[i-1] < mid <= u[i]`` (or i = 0 when the history starts on
    the mid-level). A crossing bounds a cycle only when the displacement has left the band
    ``mid +- crossing_band * max|u - mid|`` downward before it and leaves it upward after it (the
    last of several crossings in between); a history ending on the mid-level from below closes
    its last cycle there. A cycle counts only if its smaller excursion is at least
    ``min_excursion`` times the larger. The lead-in and an incomplete last cycle are dropped; a
    rest on the mid-level reached from below belongs to the next cycle.

    Parameters
    ----------
    displacement : array_like
        Displacement history [m].
    mid_level : float or "median"
        Level whose upward crossings bound the cycles [m]; "median" takes the history's median
        (for a history with an offset).
    crossing_band : float
        Half-width of the noise band, a fraction in [0, 1) of the largest excursion of the whole
        history [-]. Cycles smaller than the band are not found: analyse the blocks of a sequence
        of very different amplitudes one by one.
    min_excursion : float
        Smallest ratio of the smaller to the larger excursion of a cycle, in [0, 1] [-].

    Returns
    -------
    list of (int, int)
        ``(start, stop)`` per cycle: the samples ``u[start:stop]`` lie inside the cycle, its
        opening crossing just before ``start`` (or on it) and its closing crossing between
        ``stop - 1`` and ``stop``; consecutive cycles share a bound (stop == next start).
    """
    owner = "find_cycles"
    u = check_array(displacement, "displacement", owner, min_length=2)
    mid = _mid_level(u, mid_level, owner)
    band = check_real(crossing_band, "crossing_band", owner, low=0.0, high=1.0, high_open=True)
    ratio = check_real(min_excursion, "min_excursion", owner, low=0.0, high=1.0)
    return _find_cycles(u - mid, band, ratio)


def _crossing_value(values: np.ndarray, excursion: np.ndarray, i: int, at_level: float) -> float:
    """``values`` interpolated linearly to the upward crossing at index i."""
    e0, e1 = excursion[i - 1], excursion[i]
    if abs(e1) <= at_level:
        return float(values[i])  # sample i lies on the level (always so for i == 0)
    s = -e0 / (e1 - e0)  # in (0, 1) since e0 < 0 < e1
    return float(values[i - 1] + s * (values[i] - values[i - 1]))


def magnitude(values: np.ndarray) -> np.ndarray:
    """|x| of (n,) values, |(x, y)| of (n, 2) values, in their unit."""
    return np.abs(values) if values.ndim == 1 else np.hypot(values[:, 0], values[:, 1])


def path_integral(displacement: np.ndarray, force: np.ndarray) -> float:
    """Integral of F . du along a path by the trapezoid rule [J], for a displacement [m] and a
    force [N] of shape (n,) or (n, 2) (the EDC of a closed loop)."""
    du = np.diff(displacement, axis=0)
    return float(np.sum(0.5 * (force[1:] + force[:-1]) * du))


def least_squares_slope(displacement: np.ndarray, force: np.ndarray) -> float:
    """Slope of the least-squares line of force on displacement [N/m]."""
    du = displacement - displacement.mean()
    return float(np.dot(du, force - force.mean()) / np.dot(du, du))


def _branch_slope(
    u: np.ndarray, f: np.ndarray, low: float, high: float, cycle: int, branch: str
) -> float:
    inside = (u >= low) & (u <= high)
    if np.count_nonzero(inside) < 2 or np.ptp(u[inside]) == 0.0:
        raise InputError(
            f"Cycle {cycle} has fewer than 2 distinct samples on its {branch} branch between "
            f"{low!r} and {high!r} m: sample the history more finely or lower "
            f"'transition_fraction'."
        )
    return least_squares_slope(u[inside], f[inside])


def cycle_characteristics(
    displacement: object,
    force: object,
    time: object | None = None,
    *,
    mid_level: float | str = 0.0,
    crossing_band: float = 0.05,
    min_excursion: float = 0.3,
    transition_fraction: float = 0.1,
) -> list[CycleCharacteristics]:
    """Force-deflection characteristics of every complete cycle (paper Fig. 7, Eq. 9-11).

    Parameters
    ----------
    displacement, force : array_like
        Displacement u [m] and horizontal force F [N] histories of one length.
    time : array_like or None
        Strictly increasing sample times [s], for the cycles' start and stop times only.
    mid_level, crossing_band, min_excursion
        How cycles are found (:func:`find_cycles`).
    transition_fraction : float
        Part f in [0, 0.5) of the stroke ``s = Dmax - Dmin`` left out of the least-squares fits
        at each end of a branch [-] (the transition after each reversal): the fits use the
        samples with ``Dmin + f s <= u <= Dmax - f s``.

    Notes
    -----
    The samples before the largest displacement and after the smallest form the upper branch
    (moving in +u), those between them the lower one. EDC is positive for a dissipative loop.
    Eq. 10-11 are taken peak to peak, ``Dmax - Dmin`` and ``Fmax - Fmin`` (equal to
    ``|Dmax| + |Dmin|`` and ``|Fmax| + |Fmin|`` for a loop around the origin).

    Raises
    ------
    ValueError
        For mismatched lengths, non-finite values, bad parameters, or a history without a
        complete cycle.
    """
    owner = "cycle_characteristics"
    u = check_array(displacement, "displacement", owner, min_length=3)
    f = check_array(force, "force", owner, min_length=3, length_of=("displacement", u.size))
    t = None
    if time is not None:
        t = check_array(time, "time", owner, min_length=3)
        if t.shape != u.shape or np.any(np.diff(t) <= 0.0):
            raise InputError(
                f"The 'time' parameter of {owner} must be strictly increasing with the length "
                f"of 'displacement' ({u.size}). Got {t.size} values instead."
            )
    mid = _mid_level(u, mid_level, owner)
    band = check_real(crossing_band, "crossing_band", owner, low=0.0, high=1.0, high_open=True)
    ratio = check_real(min_excursion, "min_excursion", owner, low=0.0, high=1.0)
    frac = check_real(
        transition_fraction, "transition_fraction", owner, low=0.0, high=0.5, high_open=True
    )
    e = u - mid
    at_level = _AT_MID_LEVEL * float(np.max(np.abs(e)))
    cycles = _find_cycles(e, band, ratio)
    if not cycles:
        raise InputError(
            f"The 'displacement' parameter of {owner} must hold at least one complete cycle "
            f"(from an upward crossing of the mid-level {mid:g} m, beyond the band of "
            f"{band:g} of the largest excursion on both sides, back to the next upward "
            f"crossing). Got none in {u.size} samples instead."
        )
    results = []
    for number, (start, stop) in enumerate(cycles, start=1):
        uc, fc = u[start:stop], f[start:stop]
        # Closed loop: both ends exactly on the mid-level, forces interpolated to the crossings.
        path_u = np.concatenate([[mid], uc, [mid]])
        path_f = np.concatenate(
            [[_crossing_value(f, e, start, at_level)], fc, [_crossing_value(f, e, stop, at_level)]]
        )
        edc = path_integral(path_u, path_f)
        i_max, i_min = int(np.argmax(uc)), int(np.argmin(uc))
        d_max, d_min = float(uc[i_max]), float(uc[i_min])
        f_max, f_min = float(fc.max()), float(fc.min())
        low, high = d_min + frac * (d_max - d_min), d_max - frac * (d_max - d_min)
        up = np.r_[0:i_max, i_min + 1 : uc.size]  # moving in +u
        k_ru = _branch_slope(uc[up], fc[up], low, high, number, "upper")
        k_rl = _branch_slope(
            uc[i_max + 1 : i_min], fc[i_max + 1 : i_min], low, high, number, "lower"
        )
        k_ra = 0.5 * (abs(k_ru) + abs(k_rl))  # Eq. (9)
        k_eff = (f_max - f_min) / (d_max - d_min)  # Eq. (10), peak to peak
        # Eq. (11); NaN for a constant force (k_eff = 0, EDC = 0)
        beta = 2.0 / np.pi * edc / (k_eff * (d_max - d_min) ** 2) if k_eff != 0.0 else np.nan
        t0 = None if t is None else _crossing_value(t, e, start, at_level)
        t1 = None if t is None else _crossing_value(t, e, stop, at_level)
        results.append(
            CycleCharacteristics(
                cycle=number, start=start, stop=stop, Dmax=d_max, Dmin=d_min,
                Fmax=f_max, Fmin=f_min, Kru=k_ru, Krl=k_rl, Kra=k_ra, EDC=edc,
                Keff=k_eff, beta_eff=float(beta), start_time=t0, stop_time=t1,
            )
        )  # fmt: skip
    return results
