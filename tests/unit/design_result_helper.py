"""A DesignResult built for the report's tests without the response-history analysis: the real
ELF of ``examples/five_storey_plan.toml``, a small peaks table of 7 pairs (2 synthetic) at both
bounds and four positions, their averages and envelope, checks that pass and one that fails,
and a real short run of the plan building under a synthetic pair as the governing run (with
floor spectra)."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
BUILDING = ROOT / "examples" / "five_storey_plan.toml"
PAIRS = ("CHY023", "ILA061", "TAP084", "TAP094", "synthetic-1", "synthetic-2", "synthetic-3")
POSITIONS = ("+x", "-x", "+y", "-y")
_MIN = ("axial_load_min", "mu_min")


@lru_cache(maxsize=1)
def governing_run():
    """A 6 s run of the plan building (precise model) under a synthetic pair, floor spectra."""
    import structures
    from groundmotions import synthetic_pair

    config = structures.load_config(BUILDING)
    pair = synthetic_pair("kanai-tajimi", 3, duration=6.0, dt=0.01, target_pga=4.0,
                          ground_frequency=12.0, ground_damping=0.6)
    result = structures.run(config, pair, floor_spectra=True)
    result.attrs.update(pair="synthetic-1", bound="lower", position="+x", scale=1.0,
                        property_modifier=0.6, synthetic=1)
    return result


def make_result(*, governing: bool = True, compliant: bool = True, floor_spectra: bool = True):
    """A DesignResult of the contract (:mod:`structures.design.result`)."""
    import pandas as pd

    import structures
    from structures.design import PropertyModification, Site, elf
    from structures.design.limits import LIMITS, limit
    from structures.design.result import (
        PEAK_UNITS,
        Check,
        DesignResult,
        PairInfo,
        ScaledSpectra,
        Table,
    )

    config = structures.load_config(BUILDING)
    site = Site(1.5, 0.6, 8.0)
    result_elf = elf(config, site, PropertyModification.overall(1.8, 0.6), R=2.0)
    rng = np.random.default_rng(7)
    pairs = tuple(PairInfo(name, name.startswith("synthetic"), float(rng.uniform(0.6, 3.0)),
                           () if name.startswith("synthetic") else (f"{name}-N.AT2",
                                                                    f"{name}-W.AT2"))
                  for name in PAIRS)
    rows = []
    for pair in pairs:
        for bound in ("upper", "lower"):
            d = result_elf.bounds[bound].D_M
            for position in POSITIONS:
                row = {"pair": pair.name, "synthetic": pair.synthetic, "bound": bound,
                       "position": position, "status": "done"}
                centre = d * rng.uniform(0.8, 1.1)
                corner = centre * rng.uniform(1.02, 1.1)
                values = {
                    "isolator_displacement": corner, "centre_displacement": centre,
                    "corner_displacement": corner, "corner_centre_ratio": corner / centre,
                    "isolator_displacement_x": 0.8 * corner,
                    "isolator_displacement_y": 0.7 * corner,
                    "base_shear_x": 3.0e6 * rng.uniform(0.9, 1.1),
                    "base_shear_y": 2.8e6 * rng.uniform(0.9, 1.1),
                    "storey_shear_x": 2.5e6 * rng.uniform(0.9, 1.1),
                    "storey_shear_y": 2.4e6 * rng.uniform(0.9, 1.1),
                    "max_drift_ratio_x": 0.003 * rng.uniform(0.8, 1.2),
                    "max_drift_ratio_y": 0.0028 * rng.uniform(0.8, 1.2),
                    "roof_acceleration_x": 2.0 * rng.uniform(0.8, 1.2),
                    "roof_acceleration_y": 1.9 * rng.uniform(0.8, 1.2),
                    "axial_load_max": 2.6e6 * rng.uniform(1.0, 1.4),
                    "axial_load_min": 0.8e6 * rng.uniform(0.5, 1.0),
                    "max_temperature": 20.0 + 120.0 * rng.uniform(0.5, 1.0),
                    "mu_min": 0.03 * rng.uniform(0.8, 1.0),
                    "mu_max": 0.12 * rng.uniform(1.0, 1.2),
                }
                row.update(values)
                for k in range(1, 6):
                    row[f"drift_ratio_x_{k}"] = 0.003 * (1.1 - 0.15 * k) * rng.uniform(0.9, 1)
                    row[f"drift_ratio_y_{k}"] = 0.0028 * (1.1 - 0.15 * k) * rng.uniform(0.9, 1)
                rows.append(row)
    peaks = pd.DataFrame(rows)
    columns = [c for c in peaks.columns if c in PEAK_UNITS or c.startswith("drift_ratio_")]
    averages = peaks.groupby(["bound", "position"], sort=False)[columns].mean().reset_index()
    envelope = {}
    for column in columns:
        values = averages[column]
        k = int(values.idxmin() if column in _MIN else values.idxmax())
        envelope[column] = {"value": float(values[k]), "unit": PEAK_UNITS.get(column, "-"),
                            "bound": averages["bound"][k], "position": averages["position"][k]}
    d_tm = max(result_elf.bounds[b].directions[x].D_TM for b in ("upper", "lower")
               for x in ("x", "y"))
    checks = (
        Check("suite_size", LIMITS["min_pairs"].clause, "pairs of ground motions",
              float(len(pairs)), limit("min_pairs"), "-", kind="min"),
        Check("rha_D_TM_vs_elf", "17.6.4", "isolator displacement of the response history "
              "against 80 % of the ELF's D_TM", envelope["isolator_displacement"]["value"],
              limit("rha_D_TM_min") * d_tm, "m", kind="min",
              bound=envelope["isolator_displacement"]["bound"],
              position=envelope["isolator_displacement"]["position"]),
        Check("rha_V_b_vs_elf_x", "17.6.4", "base shear x against 90 % of the ELF's V_b",
              envelope["base_shear_x"]["value"], 0.9 * result_elf.upper.V_b, "N", kind="min",
              bound="upper", position="+x"),
        Check("drift_ratio_x", "17.6.4.4", "largest storey drift ratio x",
              envelope["max_drift_ratio_x"]["value"], limit("drift_rha"), "-",
              bound="upper", position="+y"),
        Check("displacement_capacity", "17.2.4", "bearing displacement against its capacity",
              envelope["isolator_displacement"]["value"], 0.6, "m"),
        Check("uplift", "17.2.4.7", "smallest bearing axial load (no uplift)",
              envelope["axial_load_min"]["value"], 0.0, "N", kind="min"),
    )
    lo, hi = 0.75 * result_elf.upper.T_M, 1.25 * result_elf.lower.T_M
    periods = np.geomspace(0.1, 8.0, 50)
    target = np.where(periods < 0.6 / 1.5, 1.5, 0.6 / periods)
    spectra = ScaledSpectra(periods, target, {
        p.name: target * rng.uniform(0.6, 1.4, periods.size) for p in pairs}, (lo, hi))
    tables = (
        Table("Ground-motion suite and scale factors", "17.3.2, 17.3.3",
              ("pair", "synthetic", "scale factor", "sources"), ("", "", "-", ""),
              tuple((p.name, p.synthetic, p.scale_factor, "; ".join(p.sources))
                    for p in pairs), "one factor per pair"),
        Table("Envelope of the averages over bounds and positions", "17.6.3.4",
              ("quantity", "unit", "value", "bound", "position"), ("", "", "", "", ""),
              tuple((k, v["unit"], v["value"], v["bound"], v["position"])
                    for k, v in envelope.items() if not k.startswith("drift_ratio_"))),
    )
    run = None
    if governing:
        run = governing_run()
        if not floor_spectra:
            run = run.drop_vars(["floor_spectrum", "ground_spectrum"])
    notes = ["3 synthetic pair(s) complete the suite: synthetic-1, synthetic-2, synthetic-3"]
    if not compliant:
        notes.insert(0, "NOT COMPLIANT: fewer than 7 pairs")
    return DesignResult(
        config.name, result_elf, pairs, compliant, spectra, peaks, averages, envelope, checks,
        tables, run, tuple(notes),
        {"site": {"S_MS": 1.5, "S_M1": 0.6, "T_L": 8.0}, "R": 2.0,
         "positions": list(POSITIONS), "hold_bearing_loads": True, "store": "peaks",
         "period_range": [lo, hi], "storey_heights": [3.5] * 5})
