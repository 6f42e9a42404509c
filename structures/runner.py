"""One path from a building file and a ground motion to a result, for the command line and for
Python alike (:func:`run`).

Example
-------
>>> import structures
>>> from groundmotions.bundled import load_bundled
>>> result = structures.run("examples/five_storey.toml", load_bundled("elcentro"))  # doctest: +SKIP
>>> structures.peaks(result)["peak_isolator_displacement"]  # doctest: +SKIP
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path
from typing import Any

from dcfpb.common.errors import InputError, InputTypeError, InputWarning
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
    """Run a building file under a ground motion, with the caller's overrides, through
    :func:`structures.analysis.run` (the bearings on their shares of the weight).

    Parameters
    ----------
    config : BuildingConfig or str or Path
        A TOML building file or its loaded form (:func:`structures.config.load_config`).
    motion : GroundMotion or GroundMotionPair or str or Path
        The ground acceleration [m/s^2], or a record file (PEER .AT2 or text;
        :func:`groundmotions.readers.read_record`). A pair (x, y and optionally z) runs a
        building file with a ``[plan]`` table in plan; one record runs the building in one
        direction (that of a file with a ``[plan]`` table along x, with a warning).
    model, integrator : str or Newmark or HHT, optional
        Friction model (``"precise"``, ``"simplified"``, ``"constant"``) and time integration
        (``"newmark"``, ``"hht"`` or an instance); by default the building file's.
    dt : float, optional
        Analysis step [s]: by default the building file's, capped by the record's step with a
        warning, else :func:`structures.analysis.default_step`.
    scale : float
        Amplitude scale factor of the record(s) [-], > 0.
    engine, floor_spectra, **options
        As :func:`structures.analysis.run` (``tolerance``, ``overturning``, ...).

    Returns
    -------
    xarray.Dataset
        The result of :func:`structures.analysis.run`, ``attrs["building"]`` naming the building.

    Raises
    ------
    dcfpb.common.errors.InputError
        For a pair of records on a building file without a ``[plan]`` table.
    """
    import dataclasses

    from structures.analysis import run as run_building

    owner = "structures.run"
    if not isinstance(config, BuildingConfig):
        if not isinstance(config, str | os.PathLike):
            raise InputTypeError(f"The 'config' parameter of {owner} must be a BuildingConfig or "
                                 f"the path of a building file. Got {config!r:.80} instead.")
        config = load_config(config)
    if not isinstance(motion, GroundMotion | GroundMotionPair):
        if not isinstance(motion, str | os.PathLike):
            raise InputTypeError(f"The 'motion' parameter of {owner} must be a GroundMotion, a "
                                 "GroundMotionPair or the path of a record file. Got "
                                 f"{motion!r:.80} instead.")
        from groundmotions.readers import read_record

        motion = read_record(motion)
    if dt is not None:
        check_real(dt, "dt", owner, low=0.0, low_open=True)
    check_real(scale, "scale", "structures.run", low=0.0, low_open=True)
    if scale != 1.0:
        motion = motion.scaled(scale)
    building = config.building
    if isinstance(motion, GroundMotionPair):
        if building.plan is None:
            raise InputError(
                f"A pair of records runs a building in plan, but the building {config.name!r} "
                "has no [plan] table: give it one, or run it under one record.")
    elif building.plan is not None:
        warnings.warn(f"The building {config.name!r} has a [plan] table but runs under one "
                      "record: it runs in one direction (x) on its bearings' count; give a pair "
                      "of records to run it in plan.", InputWarning, stacklevel=2)
        building = dataclasses.replace(building, plan=None)
    bearing = dataclasses.replace(config.bearing(model), axial_load=None)  # their shares
    if dt is None and config.dt is not None:
        dt = config.dt
        if dt > motion.dt * (1.0 + 1e-12):  # the file's step, longer than the record's
            warnings.warn(f"The building {config.name!r} asks for dt = {dt:g} s ([analysis] "
                          f"dt) but {motion.name} is sampled every {motion.dt:g} s: it runs at "
                          "the record's step.", InputWarning, stacklevel=2)
            dt = motion.dt
    result = run_building(
        building, bearing, motion, config.integrator if integrator is None else integrator,
        n_bearings=config.n_bearings if building.plan is None else None, dt=dt,
        engine=engine, floor_spectra=floor_spectra, **options)
    result.attrs["building"] = config.name
    return result
