"""Tune variants of the outside panel's two one-direction misses of issue 21 (tune data only).

Two kinds of case the outside panel's tune half does not reproduce, each made several times
with the outside panel's truth sources, records, noise and files
(:mod:`validation.diagnosis.outside`), so that :mod:`validation.diagnosis.score` scores them:

- **V-A**: a precise baseline told ``--without velocity`` while the truth has a velocity effect
  of several sizes and laws (the paper's Eq. 2, an exponential rise, a Stribeck peak), on
  several protocols; one decoy with no velocity effect told the same;
- **V-B**: a play of 2-5 mm beside heating, on ASCE-like protocols (3-cycle sines at 4.26 s,
  a slow wind-like test) and others.

Every case is labelled ``half: "tune"`` (``design.variant`` says which kind): these are tune
data, designed from the tune designs of the two panels and the physics, never from the outside
panel's test half. The case numbers are a seeded shuffle, as in the panels. The design record's
"independent precise vs package precise" share compares the independent precise truth with the
package's Eq. 2; for a variant whose velocity law is another (VA2-VA4) that share is the law's
own difference and the label-rule warning says so; the labelled effect is the law.

    python -m validation.diagnosis.variants_1d FOLDER [--seed 2026] [--kinds A,B]
    python -m validation.diagnosis.score FOLDER --half tune [--cases case_03]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from validation.diagnosis import independent as ind
from validation.diagnosis.outside.cases import ASCE, HEAT, SINE_SET, Case, S
from validation.diagnosis.outside.write import write_panel

# precise truth (Eq. 1, 3-5, 7) without its velocity factor: the velocity effect is switched on
# with the label, in the law of each case
PRECISE_NO_VELOCITY = {"mu0": ind.MU_T0, "pressure": "paper", "temperature": "paper"}


def _velocity(law: ind.Velocity) -> dict:
    return {"base": PRECISE_NO_VELOCITY, "effects": {"velocity": {"velocity": law}}}


TOLD = {"baseline": "precise", "without": ("velocity",)}


def _play_heat(width: float, **base) -> dict:
    return {"base": base, "effects": {"backlash": {"backlash": width}, "heating": HEAT}}


# protocols of the variants (own records: amplitudes, periods and rests differ from the panels')
SLOW_FAST = (S(0.15, 2.0, 3), S(0.05, 5.0, 3, rest=900.0), S(0.015, 8.0, 2, rest=900.0))
ASCE_LONG = (S(0.15, 4.26, 3), S(0.25, 4.26, 3, rest=1200.0), S(0.03, 8.4, 2, rest=1200.0))
ASCE_TWO = (S(0.2, 4.26, 3), S(0.1, 4.26, 3, rest=300.0))
HEAT_RUN = (S(0.25, 3.0, 3), S(0.2, 2.5, 4, rest=600.0), S(0.3, 4.0, 2, rest=600.0))

VARIANTS: tuple[Case, ...] = (
    # --- V-A: precise baseline told --without velocity, a true velocity effect ---
    Case("VA1", ("velocity",), "tune", "independent", "precise truth with Eq. 2 (raw), told "
         "precise without velocity, sines at several amplitudes", SINE_SET,
         _velocity(ind.Velocity("paper")), **TOLD),
    Case("VA2", ("velocity",), "tune", "independent", "precise truth with an exponential "
         "velocity law (mu_slow / mu_fast 0.5, 20 mm/s), told precise without velocity, "
         "slow and fast tests", SLOW_FAST, _velocity(ind.Velocity("exp", ratio=0.5, speed=0.02)),
         dt=0.005, noise=0.008, **TOLD),
    Case("VA3", ("velocity",), "tune", "independent", "precise truth with an exponential "
         "velocity law (mu_slow / mu_fast 0.7, 50 mm/s), told precise without velocity, "
         "ASCE-like", ASCE, _velocity(ind.Velocity("exp", ratio=0.7, speed=0.05)),
         noise=0.006, noise_kind="ar1", rho=0.85, **TOLD),
    Case("VA4", ("velocity",), "tune", "independent", "precise truth with a Stribeck peak "
         "(40 % at rest, 30 mm/s), told precise without velocity, heat over short rests",
         HEAT_RUN, _velocity(ind.Velocity("stribeck", peak=0.4, speed=0.03)), dt=0.005,
         **TOLD),
    Case("VA5", ("velocity",), "tune", "package", "full precise model (Eq. 7), told precise "
         "without velocity, nights between tests, initial temperatures 20/22/18 degC",
         (S(0.2, 2.5, 3), S(0.1, 3.0, 3, temperature=22.0), S(0.3, 4.0, 2, temperature=18.0)),
         {"dependencies": ("pressure", "temperature")}, baseline="precise",
         without=("velocity",)),
    Case("VA6", ("velocity",), "tune", "package", "full precise model (Eq. 7), told precise "
         "without velocity, ASCE-like after nights, 200 Hz", (S(0.1, 4.26, 3), S(0.2, 4.26, 3),
                                                             S(0.02, 8.4, 2)),
         {"dependencies": ("pressure", "temperature"), "u_y": 3.0e-4}, dt=0.005, noise=0.006,
         baseline="precise", without=("velocity",)),
    Case("VA7", (), "tune", "independent", "decoy: precise truth without velocity "
         "dependence, told precise without velocity, slow and fast tests", SLOW_FAST,
         {"base": PRECISE_NO_VELOCITY}, noise=0.008, **TOLD),
    # --- V-B: a play of 2-5 mm beside heating ---
    Case("VB1", ("backlash", "heating"), "tune", "independent", "4 mm play and temperature "
         "dependence, ASCE-like, rests of 600 s", ASCE, _play_heat(0.004, yield_displacement=3e-4),
         noise=0.008),
    Case("VB2", ("backlash", "heating"), "tune", "independent", "3 mm play and temperature "
         "dependence, ASCE-like with longer rests, smooth transition", ASCE_LONG,
         _play_heat(0.003, transition="smooth", yield_displacement=5e-4), dt=0.005),
    Case("VB3", ("backlash", "heating"), "tune", "independent", "5 mm play and temperature "
         "dependence, two ASCE-like tests, rigid-plastic, AR(1) noise", ASCE_TWO,
         _play_heat(0.005, transition="rigid-plastic"), noise=0.008, noise_kind="ar1",
         rho=0.85),
    Case("VB4", ("backlash", "heating"), "tune", "independent", "2 mm play and temperature "
         "dependence, ASCE-like, 200 Hz", ASCE, _play_heat(0.002, yield_displacement=2e-4),
         dt=0.005, noise=0.006),
    Case("VB5", ("backlash", "heating"), "tune", "independent", "4 mm play and temperature "
         "dependence, heat over short rests", HEAT_RUN,
         _play_heat(0.004, yield_displacement=4e-4), dt=0.005, lag_samples=0.8),
    Case("VB6", ("backlash", "heating"), "tune", "independent", "3.5 mm play and temperature "
         "dependence, sines at several amplitudes, band-limited noise", SINE_SET,
         _play_heat(0.0035, yield_displacement=5e-4), noise_kind="band"),
)
KINDS = {"A": "precise baseline told --without velocity, a true velocity effect",
         "B": "a play of 2-5 mm beside heating"}


def write_variants(folder: str | Path, *, seed: int = 2026,
                   kinds: tuple[str, ...] = ("A", "B"), progress: bool = False) -> Path:
    """Write the variants of ``kinds`` to ``folder`` (a panel folder scored by
    :mod:`validation.diagnosis.score`, every case in the ``tune`` half) with the outside
    panel's writer; return the labels file. ``seed`` sets the case numbering and the
    measurement noise (each variant's drawn apart from the panel's cases)."""
    return write_panel(folder, seed=seed, progress=progress, cases=VARIANTS,
                       pairs=tuple(c.pair for c in VARIANTS if c.pair[1] in kinds),
                       noise_offset=1000, opensees=False,
                       variant=lambda c: f"tune variant {c.pair}: {KINDS[c.pair[1]]}",
                       panel_info={"half": "tune", "variants": "issue 21, 1D"})


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.diagnosis.variants_1d",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("folder")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--kinds", default="A,B", help="A, B or A,B")
    args = parser.parse_args(argv)
    write_variants(args.folder, seed=args.seed,
                   kinds=tuple(k.strip() for k in args.kinds.split(",")), progress=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
