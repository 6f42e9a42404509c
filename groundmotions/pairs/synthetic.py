"""Synthetic horizontal pairs (and verticals) from the filtered white-noise generators.

``synthetic_pair`` draws the x and y components from `groundmotions.kanai_tajimi` or
`groundmotions.clough_penzien` with the same parameters and two different seeds, so the two
horizontals are independent realisations of one process (statistically isotropic: no
direction is preferred), and optionally a vertical from a third seed scaled by a ratio. A pair
is reproducible from its seed: the components use ``seed``, ``seed + 1`` and ``seed + 2`` (each
one a PCG64 stream; numpy's seeding hashes the seed, so neighbouring seeds give unrelated
streams), recorded in each component's ``metadata``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from dcfpb.common.errors import InputTypeError
from dcfpb.common.validation import check_choice, check_int, check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from groundmotions.synthetic import clough_penzien, kanai_tajimi

__all__ = ["GENERATORS", "synthetic_pair"]

GENERATORS: dict[str, Callable[..., GroundMotion]] = {
    "kanai-tajimi": kanai_tajimi,
    "clough-penzien": clough_penzien,
}
"""The generators a pair can be drawn from, by name."""


def synthetic_pair(
    generator: str | Callable[..., GroundMotion],
    seed: int,
    *,
    duration: float,
    dt: float,
    vertical_ratio: float | None = None,
    name: str | None = None,
    **parameters: Any,
) -> GroundMotionPair:
    """A pair of independent synthetic horizontals (and optionally a vertical).

    Parameters
    ----------
    generator : {"kanai-tajimi", "clough-penzien"} or callable
        The generator, by name or as the function (`kanai_tajimi`, `clough_penzien` or one
        with their signature: ``(duration, dt, *, seed, name, **parameters) -> GroundMotion``).
    seed : int
        Seed of the pair, >= 0: x uses ``seed``, y ``seed + 1``, z ``seed + 2``.
    duration : float
        Record length, > 0 [s].
    dt : float
        Time step [s] (see the generator).
    vertical_ratio : float, optional
        If given, add a vertical component: a third realisation of the same process
        multiplied by this ratio, > 0 [-] (e.g. 2/3, the classical vertical-to-horizontal
        ratio; with ``target_pga`` the vertical's PGA is ``vertical_ratio * target_pga``).
    name : str, optional
        The pair's name; ``"<generator> pair (seed <seed>)"`` by default.
    **parameters
        Keyword parameters of the generator (``ground_frequency`` [rad/s],
        ``ground_damping`` [-], ``intensity`` [m^2/s^3] or ``target_pga`` [m/s^2],
        ``envelope`` ...), the same for every component.

    Returns
    -------
    GroundMotionPair
        Components named ``<name> x``, ``<name> y`` (and ``<name> z``) [m/s^2].
    """
    owner = "synthetic_pair"
    if isinstance(generator, str):
        make = GENERATORS[check_choice(generator, "generator", owner, tuple(GENERATORS))]
        label = generator
    elif callable(generator):
        make, label = generator, getattr(generator, "__name__", "synthetic")
    else:
        raise InputTypeError(f"The 'generator' parameter of {owner} must be one of "
                             f"{tuple(GENERATORS)} or a generator function. "
                             f"Got {generator!r} instead.")
    first = check_int(seed, "seed", owner, low=0)
    ratio = None if vertical_ratio is None else check_real(
        vertical_ratio, "vertical_ratio", owner, low=0.0, low_open=True)
    pair_name = name if name is not None else f"{label} pair (seed {first})"
    roles = ("x", "y") if ratio is None else ("x", "y", "z")
    motions = {role: make(duration, dt, seed=first + k, name=f"{pair_name} {role}",
                          **parameters) for k, role in enumerate(roles)}
    z = None if ratio is None else motions["z"].scaled(ratio)
    return GroundMotionPair(motions["x"], motions["y"], z, pair_name)
