"""A small campaign of bearing tests in two directions for ``dcfpb diagnose``.

Drives the package's bidirectional element (:func:`isolator.testrig.run_orbit` /
:func:`~isolator.testrig.run_test`) through a circle and a figure-eight, switches one effect
on through the friction model's parameters or the load train, adds sensor noise and writes
the tests in the two-direction format (``time``, ``displacement_x``, ``displacement_y``,
``force_x``, ``force_y``, ``axial_force``) with a TOML manifest::

    python examples/diagnose_2d_campaign.py OUT_DIR [--effect heating] [--seed 1]
    dcfpb diagnose --manifest OUT_DIR/campaign.toml --model constant

Effects: ``none`` (constant friction), ``heating`` (the precise model's heating only),
``velocity`` (the speed dependence only), ``backlash`` (a play of 4 mm along x and 2 mm
along y in the load train; an axis whose gap is open stands still and reads no force),
``lag`` (the force channel 4 samples late), or several joined by
``+`` (``heating+backlash``).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

EFFECTS = ("none", "heating", "velocity", "backlash", "lag")
RADIUS = 2.0  # [m] effective radius
SLIDER = 0.25  # [m] slider diameter
LOAD = 1.0e6  # [N] axial load
MU = 0.06
ORBITS = (("circle", 0.08, 4.0, 2), ("figure8", 0.10, 2.0, 3))
"""The default tests: (kind, size [m], period [s], cycles); for ``"earthquake"`` (
:func:`earthquake_orbit`) the size is the peak radius, the period the duration and the cycles
the seed of the path."""
PLAY = (4.0e-3, 2.0e-3)  # [m] play along x and y
LAG_SAMPLES = 4


def _play(u: np.ndarray, width: float) -> np.ndarray:
    out, half, y = np.empty_like(u), 0.5 * width, u[0]
    for i, x in enumerate(u):
        y = x - half if x - y > half else x + half if y - x > half else y
        out[i] = y
    return out


def _behind_play(u: np.ndarray, yield_displacement: float) -> tuple[np.ndarray, ...]:
    """The bearing behind the play :data:`PLAY` driven by the actuators' ``u`` (n, 2): per
    axis a motion against that axis's force first unloads the pre-sliding spring, then
    crosses the gap (the bearing standing still on that axis, no force on it), then loads
    the spring the other way; the element's isotropic return map does the loading. Returns
    the bearing's displacement, z and whether each axis transmits force (n, 2)."""
    from isolator.bearing import isotropic_return_map

    half = 0.5 * np.asarray(PLAY)
    z, gap = np.zeros(2), np.zeros(2)
    ub, zs, engaged = u.copy(), np.zeros_like(u), np.ones_like(u)
    for i in range(1, u.shape[0]):
        step = u[i] - u[i - 1]
        for j in range(2):
            r = step[j]
            if z[j] * r < 0.0:
                if abs(r) <= abs(z[j]) * yield_displacement:
                    z[j] += r / yield_displacement
                    r = 0.0
                else:
                    r += z[j] * yield_displacement
                    z[j] = 0.0
            if r != 0.0 and z[j] == 0.0:
                target = np.sign(r) * half[j]
                if abs(r) < abs(target - gap[j]):
                    gap[j] += r
                    r = 0.0
                    engaged[i, j] = 0.0
                else:
                    r -= target - gap[j]
                    gap[j] = target
            step[j] = r
        z = np.array(isotropic_return_map(z[0], z[1], step[0], step[1],
                                          yield_displacement)[:2])
        ub[i], zs[i] = u[i] - gap, z
    return ub, zs, engaged


def earthquake_orbit(peak: float, duration: float, dt: float, seed: int = 0):
    """An earthquake-like orbit: band-limited random motion (0.2-1.5 Hz, a sum of 24 sines
    per axis with random phases) under a sine-squared envelope, scaled to a peak radius
    ``peak`` [m], ``duration`` [s] long in steps of ``dt`` [s]; an
    :class:`~isolator.orbits.Orbit` with its exact velocity."""
    from isolator.orbits import Orbit

    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration + 0.5 * dt, dt)
    frequencies = rng.uniform(0.2, 1.5, (2, 24))
    phases = rng.uniform(0.0, 2 * np.pi, (2, 24))
    envelope = np.sin(np.pi * t / duration) ** 2
    d_envelope = np.pi / duration * np.sin(2 * np.pi * t / duration)
    u, v = np.empty((t.size, 2)), np.empty((t.size, 2))
    for j in range(2):
        w = 2 * np.pi * frequencies[j][:, None]
        waves = np.sin(w * t + phases[j][:, None]).sum(axis=0)
        rates = (w * np.cos(w * t + phases[j][:, None])).sum(axis=0)
        u[:, j], v[:, j] = envelope * waves, d_envelope * waves + envelope * rates
    scale = peak / float(np.max(np.hypot(*u.T)))
    return Orbit(t, scale * u, scale * v, "earthquake")


def synthesise(effect: str = "none", *, seed: int = 0, dt: float = 0.01,
               orbits=ORBITS, force_noise: float = 0.004,
               displacement_noise: float = 1.0e-5,
               colour: float = 0.0) -> list[dict[str, np.ndarray]]:
    """The tests of one campaign as column dicts (two-direction format, SI units).

    ``effect`` is one of :data:`EFFECTS`, or several joined by ``+`` (``"heating+backlash"``);
    ``force_noise`` is the force sensors' white noise
    over the peak |F| [-], ``displacement_noise`` the displacement sensors' [m]; ``colour``
    is the AR(1) coefficient of the force noise (0: white), its variance kept.
    """
    from isolator.bearing import DCFPBearing
    from isolator.friction import ConstantFriction, PTVFriction
    from isolator.heating import MonitorLine
    from isolator.orbits import orbit
    from isolator.testrig import run_orbit, run_test

    chosen = set(effect.split("+"))
    if not chosen <= set(EFFECTS):
        raise ValueError(f"effect must be one of {EFFECTS} or several joined by '+'. Got "
                         f"{effect!r}.")
    dependencies = tuple(d for e, d in (("heating", "temperature"), ("velocity", "velocity"))
                         if e in chosen)
    friction = (PTVFriction(MU, heating=MonitorLine() if "heating" in chosen else None,
                            dependencies=dependencies) if dependencies
                else ConstantFriction(MU))
    bearing = DCFPBearing(RADIUS, SLIDER, axial_load=LOAD, friction=friction,
                          yield_displacement=2.0e-4, displacement_capacity=0.3)
    rng = np.random.default_rng(seed)
    tests = []
    for kind, size, period, cycles in orbits:
        o = (earthquake_orbit(size, period, dt, seed=cycles) if kind == "earthquake"
             else orbit(kind, size, period, cycles, dt))
        u = np.array(o.displacement)
        driven = u
        if "backlash" in chosen:
            driven = np.column_stack([_play(u[:, j], PLAY[j]) for j in range(2)])
        if "backlash" in chosen:  # the bearing moves behind the play
            result = run_test(bearing, o.time, driven, name=kind)
            ub, z, engaged = _behind_play(u, 2.0e-4)
            force = LOAD * engaged * (ub / RADIUS + np.asarray(result.mu)[:, None] * z)
        else:
            result = run_orbit(bearing, o)
            force = np.array(result.force)
        if "lag" in chosen:
            late = o.time - LAG_SAMPLES * dt
            force = np.column_stack([np.interp(late, o.time, force[:, j]) for j in range(2)])
        peak = float(np.max(np.hypot(*force.T)))
        noise = rng.normal(0.0, force_noise * peak * np.sqrt(1.0 - colour**2), force.shape)
        for i in range(1, noise.shape[0]):
            noise[i] += colour * noise[i - 1]
        force = force + noise
        measured = u + rng.normal(0.0, displacement_noise, u.shape)
        tests.append({"name": kind, "time": np.array(o.time),
                      "displacement_x": measured[:, 0], "displacement_y": measured[:, 1],
                      "force_x": force[:, 0], "force_y": force[:, 1],
                      "axial_force": np.full(o.time.size, LOAD)})
    return tests


def write(tests: list[dict[str, np.ndarray]], folder: str | Path) -> Path:
    """Write the tests as CSV files and a TOML manifest ``campaign.toml`` in ``folder``."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    lines = [f"effective_radius = {RADIUS}", f"slider_diameter = {SLIDER}", ""]
    for k, test in enumerate(tests, start=1):
        name = f"{k:02d}_{test['name']}.csv"
        columns = [c for c in test if c != "name"]
        np.savetxt(folder / name, np.column_stack([test[c] for c in columns]), delimiter=",",
                   header=",".join(columns), comments="", fmt="%.9g")
        lines += ["[[test]]", f'file = "{name}"', ""]
    manifest = folder / "campaign.toml"
    manifest.write_text("\n".join(lines))
    return manifest


def main(argv: list[str] | None = None) -> int:
    """Write a campaign (see the module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--effect", default="heating",
                        help=f"one of {', '.join(EFFECTS)}, or several joined by '+'")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    print(f"wrote {write(synthesise(args.effect, seed=args.seed), args.folder)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
