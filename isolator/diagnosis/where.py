"""Where the gap lies: the residual broken down by band, and per-cycle characteristic errors.

:func:`locate` splits the held-out residual energy by cycle, accumulated travel, speed,
displacement relative to the contact radius r, axial load, distance from the last reversal
and test, and names the one or two contiguous band ranges, the second within the first, that
hold much more of it than of the samples ("71 % of the residual energy is in cycles 4-7, at
|u| < r (30 % of the samples)"). :func:`cycle_errors` compares the per-cycle EDC, Keff,
beta_eff, Fmax and Fmin (paper Eq. 9-11) of the measured and the predicted loops.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from isolator.characteristics import cycle_characteristics
from isolator.diagnosis.data import Campaign
from isolator.diagnosis.features import Features

DIMENSIONS = ("cycle", "travel", "velocity", "displacement", "axial_load", "reversal", "test")
QUANTITIES = ("EDC", "Keff", "beta_eff", "Fmax", "Fmin")
NEAR_REVERSAL_YIELDS = 3.0  # "near a reversal": within 3 u_y ...
NEAR_REVERSAL_FRACTION = 0.02  # ... or 2 % of the largest displacement, whichever is larger
_MAX_CYCLE_BANDS = 12
_MIN_LIFT = 0.1  # a band range is worth naming if it holds 10 points more residual than samples
_MAX_SAMPLE_SHARE = 0.5  # ... and covers at most half of the samples


@dataclass(frozen=True)
class Band:
    """One band of a breakdown.

    Attributes
    ----------
    label : str
        The band, e.g. ``"|u| < r"`` or ``"cycles 4-7"``.
    energy_share, sample_share : float
        Share of the residual energy and of the samples in the band [-].
    rms, bias : float
        RMS and mean of the residual in the band [N] (measured less predicted).
    """

    label: str
    energy_share: float
    sample_share: float
    rms: float
    bias: float


@dataclass(frozen=True)
class Where:
    """Breakdowns of a residual and the sentence that sums them up.

    Attributes
    ----------
    breakdowns : dict
        ``{dimension: [Band, ...]}`` in band order.
    statement, focus : str, list of (str, str)
        The sentence on where most of the residual sits, and the (dimension, band range)
        pairs it names.
    energy_share, sample_share : float
        Shares of residual energy and samples where all the focus bands hold [-].
    near_reversal : float
        The distance from a reversal counted as "near" [m].
    """

    breakdowns: dict[str, list[Band]]
    statement: str
    focus: list[tuple[str, str]]
    energy_share: float
    sample_share: float
    near_reversal: float


def near_reversal_distance(features: Features, yield_displacement: float) -> float:
    """Distance from a reversal counted as "near" [m] (see the module constants)."""
    reach = float(np.percentile(np.abs(features.displacement), 99))
    return max(NEAR_REVERSAL_YIELDS * yield_displacement, NEAR_REVERSAL_FRACTION * reach)


_PREFIX = {"cycle": "in ", "travel": "at ", "velocity": "at ", "displacement": "at ",
           "axial_load": "at ", "reversal": "", "test": "in "}


def _bands(features: Features, campaign: Campaign, near: float) -> dict[str, list]:
    """``{dimension: [(low, high, mask), ...]}`` of every breakdown, in band order."""
    f = features
    out: dict[str, list] = {}
    cycles = int(f.cycle.max())
    edges = np.unique(np.linspace(1, cycles + 1, min(cycles, _MAX_CYCLE_BANDS) + 1).astype(int))
    out["cycle"] = [(a, b, (f.cycle >= a) & (f.cycle < b))
                    for a, b in itertools.pairwise(edges)]
    travel = np.linspace(0.0, float(f.campaign_travel.max()) or 1.0, 6)
    travel[-1] = np.inf
    out["travel"] = [(a, b, (f.campaign_travel >= a) & (f.campaign_travel < b))
                     for a, b in itertools.pairwise(travel)]
    v_ref = float(np.percentile(f.speed, 99)) or 1.0
    v_edges = np.array([0.0, 0.05, 0.15, 0.3, 0.6, np.inf]) * v_ref
    out["velocity"] = [(a, b, (f.speed >= a) & (f.speed < b))
                       for a, b in itertools.pairwise(v_edges)]
    r = campaign.contact_radius
    d_edges = [0.0, 0.5 * r, r, 2.0 * r, np.inf]
    absu = np.abs(f.displacement)
    out["displacement"] = [(i, i + 1, (absu >= d_edges[i]) & (absu < d_edges[i + 1]))
                           for i in range(4)]
    n_ref = float(np.median(f.axial_force))
    if np.ptp(f.axial_force) > 0.02 * n_ref:
        ratio = f.axial_force / n_ref
        n_edges = [0.0, 0.8, 0.95, 1.05, 1.2, np.inf]
        out["axial_load"] = [(a, b, (ratio >= a) & (ratio < b))
                             for a, b in itertools.pairwise(n_edges)]
    else:
        out["axial_load"] = [(n_ref, n_ref, np.ones(len(f), bool))]
    out["reversal"] = [(0.0, near, f.since_reversal < near),
                       (near, np.inf, f.since_reversal >= near)]
    out["test"] = [(k, k, f.test == k) for k in range(len(campaign.tests))]
    return out


def _label(dim: str, low, high, campaign: Campaign) -> str:
    """The band (or merged range of bands) from ``low`` to ``high`` in words."""
    if dim == "cycle":
        return f"cycle {low}" if high - low == 1 else f"cycles {low}-{high - 1}"
    if dim == "travel":
        top = "" if np.isinf(high) else f"-{high:.3g}"
        return (f"accumulated travel {low:.3g}{top} m" if top
                else f"accumulated travel >= {low:.3g} m")
    if dim == "velocity":
        return _range_label("|v|", low * 1e3, high * 1e3, "mm/s")
    if dim == "displacement":
        names = ["0", "r/2", "r", "D", "inf"]
        return _range_label("|u|", names[low], names[high])
    if dim == "axial_load":
        if low == high:
            return f"N = {low:.4g} N (constant)"
        return _range_label("N", low, high, "N_med")
    if dim == "reversal":
        return (f"within {high * 1e3:.3g} mm of a reversal" if low == 0.0
                else f"further than {low * 1e3:.3g} mm from a reversal")
    name = campaign.tests[low].name
    return name if name.lower().startswith("test") else f"test {name}"


def _range_label(symbol: str, low, high, unit: str = "") -> str:
    unit = f" {unit}" if unit else ""
    if low in (0, 0.0, "0"):
        return f"{symbol} < {_fmt(high)}{unit}"
    if high in (np.inf, "inf"):
        return f"{symbol} >= {_fmt(low)}{unit}"
    return f"{_fmt(low)} <= {symbol} < {_fmt(high)}{unit}"


def _fmt(x) -> str:
    return x if isinstance(x, str) else f"{x:.3g}"


def locate(features: Features, prediction: np.ndarray, campaign: Campaign,
           near: float) -> Where:
    """Break the residual ``force - prediction`` down by band and say where most of it is."""
    residual = features.force - prediction
    energy = residual**2
    total = float(energy.sum()) or 1.0
    n = residual.size
    breakdowns: dict[str, list[Band]] = {}
    masks: dict[str, list[np.ndarray]] = {}
    edges: dict[str, list[tuple]] = {}
    for dim, bands in _bands(features, campaign, near).items():
        kept = [(low, high, m) for low, high, m in bands if m.any()]
        masks[dim] = [m for *_, m in kept]
        edges[dim] = [(low, high) for low, high, _ in kept]
        breakdowns[dim] = [Band(_label(dim, low, high, campaign), float(energy[m].sum()) / total,
                                float(m.mean()), float(np.sqrt(np.mean(energy[m]))),
                                float(residual[m].mean()))
                           for low, high, m in kept]
    focus, mask = [], np.ones(n, bool)
    for _ in range(2):  # the best band range, then the best one within it
        best = _best_range(energy, masks, mask, exclude={d for d, _ in focus})
        if best is None:
            break
        dim, i, j = best
        focus.append((dim, _label(dim, edges[dim][i][0], edges[dim][j][1], campaign)))
        mask &= np.any(masks[dim][i:j + 1], axis=0)
    share = float(energy[mask].sum()) / total
    sample_share = float(mask.mean())
    if focus:
        where = ", ".join(_PREFIX[dim] + label for dim, label in focus)
        statement = (f"{100 * share:.0f} % of the residual energy is {where} "
                     f"({100 * sample_share:.0f} % of the samples).")
    else:
        statement = ("The residual is spread evenly: no band holds much more of it than of "
                     "the samples.")
    return Where(breakdowns, statement, focus, share, sample_share, near)


def _best_range(energy: np.ndarray, masks: dict[str, list[np.ndarray]], within: np.ndarray,
                exclude: set[str]) -> tuple[str, int, int] | None:
    """Among the samples ``within``, the contiguous band range (one band for tests) whose
    share of the residual energy most exceeds its share of the samples, by ``_MIN_LIFT`` at
    least and covering at most ``_MAX_SAMPLE_SHARE`` of them; else None."""
    total = float(energy[within].sum())
    count = int(within.sum())
    if total <= 0.0 or count == 0:
        return None
    best, best_lift = None, _MIN_LIFT
    for dim in DIMENSIONS:
        if dim in exclude or len(masks[dim]) < 2:
            continue
        e = np.array([float(energy[m & within].sum()) / total for m in masks[dim]])
        c = np.array([float((m & within).sum()) / count for m in masks[dim]])
        widths = [0] if dim == "test" else range(len(e))
        for width in widths:
            for i in range(len(e) - width):
                j = i + width
                share, samples = e[i:j + 1].sum(), c[i:j + 1].sum()
                if samples == 0.0 or samples > _MAX_SAMPLE_SHARE:
                    continue
                if share - samples > best_lift:
                    best, best_lift = (dim, i, j), share - samples
    return best


@dataclass(frozen=True)
class CycleErrors:
    """Per-cycle characteristics of the measured and the predicted loops.

    Attributes
    ----------
    rows : list of dict
        One per cycle: ``test``, ``cycle``, and ``{quantity}_data``, ``_model``, ``_error``
        for EDC, Keff, beta_eff, Fmax, Fmin; the error is (model - data) / |data|, for the
        peak forces (which may be near zero) over half the measured range (Fmax - Fmin) / 2.
    """

    rows: list[dict]

    def rms(self, quantity: str) -> float:
        """RMS relative error of ``quantity`` over the cycles [-] (NaN without cycles)."""
        errors = [r[f"{quantity}_error"] for r in self.rows
                  if np.isfinite(r[f"{quantity}_error"])]
        return float(np.sqrt(np.mean(np.square(errors)))) if errors else float("nan")


def cycle_errors(campaign: Campaign, features: Features, prediction: np.ndarray) -> CycleErrors:
    """Characteristics of every complete cycle of every test, measured against predicted."""
    rows = []
    for k, rec in enumerate(campaign.tests):
        idx = features.test == k
        u = rec.displacement
        # cycles about zero, or about the median for a history with an offset
        mid = 0.0 if abs(np.median(u)) <= 0.05 * np.max(np.abs(u)) else "median"
        try:
            data = cycle_characteristics(u, rec.force, rec.time, mid_level=mid)
            model = cycle_characteristics(u, prediction[idx], rec.time, mid_level=mid)
        except ValueError:  # no complete cycle, or a branch too short to fit
            continue
        for d, m in zip(data, model, strict=True):
            row = {"test": rec.name, "cycle": d.cycle}
            half_range = 0.5 * (d.Fmax - d.Fmin)
            for q in QUANTITIES:
                a, b = float(getattr(d, q)), float(getattr(m, q))
                scale = half_range if q in ("Fmax", "Fmin") else abs(a)
                row[f"{q}_data"], row[f"{q}_model"] = a, b
                row[f"{q}_error"] = (b - a) / scale if scale > 0.0 and np.isfinite(a) else np.nan
            rows.append(row)
    return CycleErrors(rows)
