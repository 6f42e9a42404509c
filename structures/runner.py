"""One path from a building description and a ground motion to a result, for the command line
and for Python alike.

``structures.run(config, motion)`` takes a building file (or its :class:`BuildingConfig`) and a
record file (or a :class:`GroundMotion`), applies what the caller overrides (friction model,
integrator, step, scale) and runs :func:`structures.analysis.run`, which takes the model
objects themselves (a :class:`ShearBuilding`, a :class:`DCFPBearing` and the number of
bearings).

Example
-------
>>> import structures
>>> from groundmotions.bundled import load_bundled
>>> result = structures.run("examples/five_storey.toml", load_bundled("elcentro"))  # doctest: +SKIP
>>> structures.peaks(result)["peak_isolator_displacement"]  # doctest: +SKIP
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from dcfpb.common.errors import InputError
from dcfpb.common.validation import check_real
from groundmotions.pairs import GroundMotionPair
from groundmotions.records import GroundMotion
from structures.config import BuildingConfig, load_config
from structures.integrators import HHT, Newmark


def run(
    config: BuildingConfig | str | Path,
    motion: GroundMotion | GroundMotionPair | str | Path,
    *,
    model: str | None = None,
    integrator: Newmark | HHT | str | None = None,
    dt: float | None = None,
    scale: float = 1.0,
    engine: str = "auto",
    floor_spectra: bool = False,
    **options: Any,
):
    """Run a building under a ground motion.

    Parameters
    ----------
    config : BuildingConfig or str or Path
        The building: a TOML building file (see ``examples/five_storey.toml``) or its loaded
        form (:func:`structures.config.load_config`).
    motion : GroundMotion or GroundMotionPair or str or Path
        The ground acceleration [m/s^2], or a record file (PEER .AT2 or text;
        :func:`groundmotions.readers.read_record`). A pair (x, y and optionally z) runs the
        building in plan of a file with a ``[plan]`` table
        (:func:`structures.spatial.analysis.run_spatial`; ``floor_spectra`` does not apply).
    model : {"precise", "simplified", "constant"}, optional
        Friction model (default: the building file's).
    integrator : Newmark or HHT or {"newmark", "hht"}, optional
        Time integration (default: the building file's).
    dt : float, optional
        Analysis step [s] (default: the building file's, else the record's step divided into
        parts of at most 5 ms; :func:`structures.analysis.default_step`).
    scale : float
        Amplitude scale factor of the record [-], > 0.
    engine : {"auto", "compiled", "reference"}
        As :func:`structures.analysis.run`.
    floor_spectra : bool
        Add the 5 %-damped floor response spectra (``floor_spectrum``, ``ground_spectrum``).
    **options
        Further keywords of :func:`structures.analysis.run` (``tolerance``,
        ``max_subdivisions``, ...).

    Returns
    -------
    xarray.Dataset
        The result of :func:`structures.analysis.run` (of
        :func:`structures.spatial.analysis.run_spatial` for a pair); ``attrs["building"]``
        names the building.
    """
    from structures.analysis import run as run_building

    if not isinstance(config, BuildingConfig):
        config = load_config(config)
    if isinstance(motion, GroundMotionPair):
        if floor_spectra:
            raise InputError(
                "A building in plan runs without floor spectra: floor_spectra must be False. "
                f"Got floor_spectra={floor_spectra!r} instead.")
        return _run_pair(config, motion, model=model, integrator=integrator, dt=dt,
                         scale=scale, engine=engine, **options)
    if not isinstance(motion, GroundMotion):
        from groundmotions.readers import read_record

        motion = read_record(motion)
    check_real(scale, "scale", "structures.run", low=0.0, low_open=True)
    if scale != 1.0:
        motion = motion.scaled(scale)
    result = run_building(
        config.building, config.bearing(model), motion,
        config.integrator if integrator is None else integrator,
        n_bearings=config.n_bearings, dt=config.dt if dt is None else dt, engine=engine,
        floor_spectra=floor_spectra, **options)
    result.attrs["building"] = config.name
    return result


def _run_pair(config: BuildingConfig, pair: GroundMotionPair, *, model: str | None,
              integrator: Newmark | HHT | str | None, dt: float | None, scale: float,
              **options: Any):
    """:func:`run` for a building in plan under a pair of records."""
    import dataclasses

    from structures.spatial.analysis import run_spatial

    check_real(scale, "scale", "structures.run", low=0.0, low_open=True)
    if scale != 1.0:
        pair = pair.scaled(scale)
    bearing = dataclasses.replace(config.bearing(model), axial_load=None)  # the shares
    result = run_spatial(config.spatial_building(), bearing, pair,
                         config.integrator if integrator is None else integrator,
                         dt=config.dt if dt is None else dt, **options)
    result.attrs["building"] = config.name
    return result
