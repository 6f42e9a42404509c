"""Truth models for the diagnosis's validation panel: richer than the baseline it is told.

A truth drives a bearing through an imposed displacement history and returns what a test machine
would record before noise: our element with effects the baseline lacks (PTV friction, another
effective radius, :class:`Breakaway`, :class:`Wear`), or an OpenSees element
(``FPBearingPTV``, ``singleFPBearing`` with ``VelDependent`` or ``Coulomb`` friction).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from isolator.bearing import AxialLoadHistory, DCFPBearing
from isolator.protocols import ImposedHistory
from isolator.testrig import run_test


@dataclass(frozen=True)
class Breakaway:
    """Static friction peak after each reversal, m = 1 + ``ratio`` (1 - s / ``length``)^2 for
    s < ``length``: ``ratio`` [-] the extra friction at a reversal (and at the start of motion),
    ``length`` [m] the travel s since it over which the peak fades."""

    ratio: float = 0.35
    length: float = 0.01

    def factor(self, displacement: np.ndarray) -> np.ndarray:
        """m(t) [-] for a clean displacement history [m]."""
        u = np.asarray(displacement, dtype=float)
        du = np.diff(u)
        sign = np.sign(du)
        for i in range(1, sign.size):  # a pause keeps the direction of motion
            if sign[i] == 0.0:
                sign[i] = sign[i - 1]
        turns = np.concatenate([[0], np.flatnonzero(sign[1:] * sign[:-1] < 0.0) + 1])
        segment = np.searchsorted(turns, np.arange(u.size), side="right") - 1
        since = np.abs(u - u[turns][segment])
        return 1.0 + self.ratio * np.clip(1.0 - since / self.length, 0.0, None) ** 2


@dataclass(frozen=True)
class Wear:
    """Friction drifting with the campaign's accumulated travel S, m = 1 + ``change``
    (S / ``campaign_travel``)^``power``: ``change`` [-] the relative change at the end of the
    campaign (negative: run-in), ``campaign_travel`` [m] the whole travel (set by the panel)."""

    change: float = -0.2
    power: float = 0.6
    campaign_travel: float = 1.0

    def factor(self, travel: np.ndarray) -> np.ndarray:
        """m(t) for the accumulated travel of the campaign at each sample [-]."""
        return 1.0 + self.change * (np.asarray(travel) / self.campaign_travel) ** self.power


@dataclass(frozen=True)
class TruthRecord:
    """A truth's clean output: time [s], displacement [m], velocity [m/s], force [N],
    axial force [N] (one value per sample)."""

    time: np.ndarray
    displacement: np.ndarray
    velocity: np.ndarray
    force: np.ndarray
    axial_force: np.ndarray


def element_truth(
    bearing: DCFPBearing,
    history: ImposedHistory,
    *,
    axial_load: np.ndarray | None = None,
    breakaway: Breakaway | None = None,
    wear: Wear | None = None,
    travel_before: float = 0.0,
) -> TruthRecord:
    """Our element (:func:`isolator.testrig.run_test`) as the true ``bearing`` (friction model,
    effective radius) through the imposed ``history`` [m, m/s], optionally under an
    ``axial_load`` [N] per sample instead of its constant one, and with ``breakaway`` or
    ``wear`` on its friction force, the campaign having travelled ``travel_before`` [m]."""
    t, u, v = history.time, history.displacement, history.velocity
    if axial_load is not None:
        bearing = replace(bearing, axial_load=AxialLoadHistory(t - t[0], axial_load))
    result = run_test(bearing, t, u, v, name=history.name)
    friction = result.friction_force.copy()
    if breakaway is not None:
        friction *= breakaway.factor(u)
    if wear is not None:
        travel = travel_before + np.concatenate([[0.0], np.cumsum(np.abs(np.diff(u)))])
        friction *= wear.factor(travel)
    force = result.force - result.friction_force + friction
    return TruthRecord(t, u, v, force, result.axial_load.copy())


def opensees_truth(bearing: DCFPBearing, history: ImposedHistory, element: str) -> TruthRecord:
    """An OpenSees ``element`` through ``history``
    (:func:`structures.opensees.bearing.run_opensees_test`), recording the bearing's constant
    axial load (what a test machine's vertical actuator holds)."""
    from structures.opensees.bearing import run_opensees_test

    result = run_opensees_test(bearing, history.time, history.displacement, history.velocity,
                               element=element, name=history.name)
    load = np.full(result.time.size, bearing.axial_load_at(0.0))
    return TruthRecord(result.time, result.displacement, result.velocity, result.force, load)


def measured(truth: TruthRecord, rng: np.random.Generator, *, force_noise: float,
             displacement_noise: float, velocity_noise: float | None,
             axial_noise: float | None) -> dict[str, np.ndarray]:
    """The columns a test machine would write: the truth plus white measurement noise of the
    standard deviations ``force_noise`` [N], ``displacement_noise`` [m], ``velocity_noise``
    [m/s] and ``axial_noise`` (relative) [-], drawn from ``rng``; None leaves that column out."""
    n = truth.time.size
    out = {"time": truth.time,
           "displacement": truth.displacement + rng.normal(0.0, displacement_noise, n),
           "force": truth.force + rng.normal(0.0, force_noise, n)}
    if velocity_noise is not None:
        out["velocity"] = truth.velocity + rng.normal(0.0, velocity_noise, n)
    if axial_noise is not None:
        out["axial_force"] = truth.axial_force * (1.0 + rng.normal(0.0, axial_noise, n))
    return out
