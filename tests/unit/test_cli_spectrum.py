"""``dcfpb spectrum``: text and JSON output, chosen periods, the plot, and clear errors."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.units import STANDARD_GRAVITY
from groundmotions.bundled import load_bundled
from groundmotions.processing import arias_intensity, significant_duration
from groundmotions.spectra import peak_ground_values, spectrum

REPO = Path(__file__).resolve().parents[2]
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"


def _json(capsys, *extra):
    assert main(["spectrum", str(RECORD), "--json", *extra]) == 0
    return json.loads(capsys.readouterr().out)


def test_json_values_are_the_library_values(capsys):
    out = _json(capsys)
    motion = load_bundled("elcentro")
    pga, pgv, pgd = peak_ground_values(motion.acceleration, motion.dt)
    assert (out["pga"], out["pgv"], out["pgd"]) == (pga, pgv, pgd)
    assert out["pga_g"] == pytest.approx(0.3188, abs=1e-4)
    assert out["arias_intensity"] == arias_intensity(motion)[1][-1]
    assert out["d5_75"] == significant_duration(motion, 0.05, 0.75)
    assert out["d5_95"] == significant_duration(motion, 0.05, 0.95)
    assert (out["npts"], out["dt"], out["damping"]) == (1559, 0.02, 0.05)
    rows = out["spectrum"]
    assert [r["period"] for r in rows][:3] == [0.0, 0.05, 0.1] and len(rows) == 13
    assert rows[0]["sa"] == pga and rows[0]["sd"] == 0.0
    reference = spectrum(motion, [r["period"] for r in rows], 0.05)
    np.testing.assert_allclose([r["sa"] for r in rows], reference.sa, rtol=1e-14)
    np.testing.assert_allclose([r["sd"] for r in rows], reference.sd, rtol=1e-14)


def test_periods_and_damping_options(capsys):
    out = _json(capsys, "--periods", "0.5", "1", "2", "--damping", "0.02")
    assert [r["period"] for r in out["spectrum"]] == [0.5, 1.0, 2.0]
    assert out["damping"] == 0.02
    five = _json(capsys, "--periods", "0.5", "1", "2")
    assert all(a["sa"] > b["sa"] for a, b in zip(out["spectrum"], five["spectrum"],
                                                  strict=True))
    for row in out["spectrum"]:
        omega = 2 * np.pi / row["period"]
        assert row["sv"] == pytest.approx(omega * row["sd"], rel=1e-14)
        assert row["sa"] == pytest.approx(omega**2 * row["sd"], rel=1e-14)


def test_text_output_names_every_quantity(capsys):
    assert main(["spectrum", str(RECORD)]) == 0
    text = capsys.readouterr().out
    for word in ("PGA 3.127 m/s^2 (0.3188 g)", "PGV", "PGD", "Arias intensity", "D5-75",
                 "D5-95", "Sd [m]", "Sv [m/s]", "Sa [m/s2]", "damping 0.05"):
        assert word in text, word
    assert len([line for line in text.splitlines() if line.strip()[:1].isdigit()]) == 13


def test_plot_writes_a_png(tmp_path, capsys):
    png = tmp_path / "spectra.png"
    assert main(["spectrum", str(RECORD), "--plot", str(png)]) == 0
    capsys.readouterr()
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert png.stat().st_size > 20_000


def test_a_two_column_text_record_in_g(tmp_path, capsys):
    t = np.arange(1001) * 0.01
    path = tmp_path / "sine.txt"
    np.savetxt(path, np.column_stack([t, 0.2 * np.sin(2 * np.pi * t)]), header="time a[g]")
    assert main(["spectrum", str(path), "--json", "--periods", "1.0"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pga"] == pytest.approx(0.2 * STANDARD_GRAVITY, rel=1e-6)
    assert out["spectrum"][0]["sa"] > 2 * out["pga"]  # resonance at T = 1 s


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (["--damping", "1.5"], ["'--damping'", "[0, 1)", "1.5"]),
        (["--periods", "-1"], ["'--periods'", "-1"]),
    ],
)
def test_bad_values_are_clear_errors_with_exit_status_2(capsys, extra, words):
    assert main(["spectrum", str(RECORD), *extra]) == 2
    err = capsys.readouterr().err
    assert err.startswith("dcfpb spectrum: error:")
    for word in words:
        assert word in err


def test_a_missing_file_is_an_error(tmp_path, capsys):
    assert main(["spectrum", str(tmp_path / "nothing.at2")]) == 2
    assert "nothing.at2" in capsys.readouterr().err
