"""Bad-input panel, part 3 (issue 22): the channels, header and size of ``dcfpb diagnose``'s
test files and the manifest against the flags.

Each case is one call, through the command line in-process (``dcfpb.cli.main``) or through
the Python API, on inputs written to ``tmp_path``. Each asserts (a) the exit status (2: bad
input) or the exception class, (b) that the message names the file, column, key or flag
concerned, and (c) that no input file and no earlier output in ``tmp_path`` changed (their
hashes before and after the call). Every case is refused before any fitting, so the whole
panel takes a few seconds.
"""

from __future__ import annotations

import gzip
import hashlib
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import isolator.diagnosis.data as data
from dcfpb.cli import main
from dcfpb.common.errors import InputError, InputTypeError
from isolator.diagnosis import BearingRecord, DataError, load_campaign, read_record
from isolator.diagnosis.manifest import load_manifest

N = 4.24e6  # [N] axial load
R_EFF = 4.5  # [m]
DIAMETER = 0.3  # [m]
ROWS = 500


def _columns() -> dict[str, np.ndarray]:
    """A pendulum test at 100 Hz [s, m, N, m/s] with noise on every channel."""
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 5.0, 0.01)
    u = 0.1 * np.sin(2.0 * np.pi * t / 2.5)
    v = 0.1 * 2.0 * np.pi / 2.5 * np.cos(2.0 * np.pi * t / 2.5)
    f = N * u / R_EFF + 0.04 * N * np.tanh(v / 0.01)
    return {"time": t, "displacement": u + rng.normal(0.0, 2e-5, t.size),
            "force": f + rng.normal(0.0, 1.0e3, t.size),
            "velocity": v + rng.normal(0.0, 2e-3, t.size)}


GOOD = _columns()


def _write(path: Path, columns: dict[str, np.ndarray], header: str | None = None) -> str:
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",",
               header=header or ",".join(columns), comments="", fmt="%.10g")
    return str(path)


def _with(**changes) -> dict[str, np.ndarray]:
    return GOOD | {k: np.asarray(v, dtype=float) for k, v in changes.items()}


def _cli(*files: str, extra: tuple[str, ...] = (), load: bool = True) -> list[str]:
    args = ["diagnose", *files, "--model", "constant", "--effective-radius", str(R_EFF),
            "--slider-diameter", str(DIAMETER), *extra]
    return args + (["--axial-load", repr(N)] if load else [])


def _sparse(path: Path, size: int = 10**9) -> str:
    """A CSV file of ``size`` bytes: a header and ten rows, the rest a hole (no disk used)."""
    lines = ["time,displacement,force"] + [f"{0.01 * i:.2f},{1e-3 * i:.4f},{1000.0 * i:.1f}"
                                           for i in range(10)]
    path.write_text("\n".join(lines) + "\n")
    with path.open("r+b") as handle:
        handle.truncate(size)
    return str(path)


def _manifest(tmp: Path, text: str, name: str = "m.csv") -> str:
    (tmp / name).write_text(text)
    return str(tmp / name)


# Each builder writes its inputs to tmp and returns (the call, the names its message must
# hold): the call is a CLI argv (exit status 2 expected) or a function (the exception class
# of the case expected).
Builder = Callable[[Path], tuple[list[str] | Callable[[], object], tuple[str, ...]]]


def _v(factor: float, name: str = "v.csv", header: str | None = None) -> Builder:
    def build(tmp):
        return _cli(_write(tmp / name, _with(velocity=factor * GOOD["velocity"]), header)), \
            (name, "column 'velocity'")
    return build


def _t(values, header: str | None = None) -> Builder:
    def build(tmp):
        return _cli(_write(tmp / "t.csv", _with(temperature=values), header)), \
            ("t.csv", "column 'temperature'")
    return build


def _header(header: str, *names: str) -> Builder:
    def build(tmp):
        width = header.count(",") + 1
        values = (list(GOOD.values()) + [GOOD["force"]] * 4)[:width]
        return _cli(_write(tmp / "h.csv", dict(enumerate(values)), header)), ("h.csv", *names)
    return build


def _wide(tmp):
    return _cli(_write(tmp / "wide.csv", GOOD, "time,displacement,force")), \
        ("wide.csv", "3 column(s)")


def _start_in_kelvin(tmp):
    _write(tmp / "a.csv", GOOD)
    manifest = _manifest(tmp, f"file,axial_load,initial_temperature\na.csv,{N},293.15\n")
    return _cli(extra=("--manifest", manifest), load=False), \
        ("m.csv: test 1", "'initial_temperature'", "293.15", "kelvin")


def _velocity_noise(tmp):
    noise = np.random.default_rng(5).normal(0.0, 0.2, ROWS)
    return _cli(_write(tmp / "v.csv", _with(velocity=noise))), ("v.csv", "column 'velocity'")


def _velocity_gz(tmp):
    plain = Path(_write(tmp / "plain.csv", _with(velocity=1e3 * GOOD["velocity"])))
    (tmp / "v.csv.gz").write_bytes(gzip.compress(plain.read_bytes()))
    return _cli(str(tmp / "v.csv.gz")), ("v.csv.gz", "column 'velocity'", "mm/s")


def _velocity_in_memory(tmp):
    def call():
        return BearingRecord("bench", GOOD["time"], GOOD["displacement"], GOOD["force"],
                             np.full(ROWS, N), velocity=1e3 * GOOD["velocity"])
    return call, ("test 'bench'", "column 'velocity'", "mm/s")


def _temperature_in_memory(tmp):
    def call():
        return BearingRecord("bench", GOOD["time"], GOOD["displacement"], GOOD["force"],
                             np.full(ROWS, N), temperature=np.full(ROWS, 1200.0))
    return call, ("test 'bench'", "column 'temperature'", "1200.0")


def _duplicate_in_manifest(tmp):
    _write(tmp / "dup.csv", dict(enumerate([*GOOD.values(), GOOD["force"]])),
           "time,displacement,force,velocity,force")
    manifest = _manifest(tmp, f"file,axial_load\ndup.csv,{N}\n")
    return _cli(extra=("--manifest", manifest), load=False), \
        ("m.csv", "dup.csv", "'force' appears twice")


def _toml(flag: str, key: str, given: str) -> Builder:
    def build(tmp):
        _write(tmp / "a.csv", GOOD)
        manifest = _manifest(tmp, f"effective_radius = {R_EFF}\nslider_diameter = {DIAMETER}\n"
                             f'[[test]]\nfile = "a.csv"\naxial_load = {N}\n', "m.toml")
        return ["diagnose", "--manifest", manifest, "--model", "constant", flag, given], \
            ("m.toml", f"'{key}'", flag, given)
    return build


def _csv_manifest_second_row(tmp):
    _write(tmp / "a.csv", GOOD)
    manifest = _manifest(tmp, f"file,axial_load\na.csv,\na.csv,{2 * N}\n")
    return _cli(extra=("--manifest", manifest)), \
        ("m.csv: test 2 (a.csv)", "'axial_load'", "--axial-load", repr(N))


def _size_sparse(tmp):
    return _cli(_sparse(tmp / "huge.csv")), ("huge.csv", "2,000,000 rows", "--max-rows")


def _size_gz(tmp):
    body = b"time,displacement,force\n" + b"0.0100000,0.0010000,1000.0000\n" * 2_500_000
    (tmp / "big.csv.gz").write_bytes(gzip.compress(body, compresslevel=1))
    return _cli(str(tmp / "big.csv.gz")), ("big.csv.gz", "2,000,000 rows")


def _max_rows(value: str) -> Builder:
    def build(tmp):
        return _cli(_write(tmp / "a.csv", GOOD), extra=("--max-rows", value)), \
            ("--max-rows", value) if int(value) < 1 else ("a.csv", "--max-rows", "500")
    return build


def _size_memory(tmp):
    data.available_memory = lambda: 4_096  # restored by the test (monkeypatch)
    return _cli(_write(tmp / "a.csv", GOOD)), ("a.csv", "4.1 kB available")


def _size_manifest(tmp):
    _sparse(tmp / "huge.csv")
    manifest = _manifest(tmp, f"file,axial_load\nhuge.csv,{N}\n")
    return _cli(extra=("--manifest", manifest), load=False), \
        ("m.csv: test 1 (huge.csv)", "2,000,000 rows")


def _size_api_type(tmp):
    path = _write(tmp / "a.csv", GOOD)
    return (lambda: read_record(path, axial_load=N, max_rows="100")), ("max_rows", "'100'")


def _size_api_campaign(tmp):
    good, huge = _write(tmp / "a.csv", GOOD), _sparse(tmp / "huge.csv")
    return (lambda: load_campaign([good, huge], effective_radius=R_EFF,
                                  slider_diameter=DIAMETER, axial_load=N)), \
        ("huge.csv", "2,000,000 rows")


def _manifest_api(tmp):
    _write(tmp / "a.csv", GOOD)
    manifest = _manifest(tmp, f"effective_radius = {R_EFF}\nslider_diameter = {DIAMETER}\n"
                         f'[[test]]\nfile = "a.csv"\naxial_load = {N}\n', "m.toml")
    return (lambda: load_manifest(manifest, effective_radius=2.0, must_agree=True)), \
        ("m.toml", "'effective_radius'", "effective_radius gives 2.0")


KELVIN = 293.15 + np.linspace(0.0, 10.0, ROWS)
HOT = np.full(ROWS, 20.0)
HOT[100] = 420.0
COLD = np.full(ROWS, 20.0)
COLD[7] = -75.0

CASES: list[tuple[str, Builder, int | type[BaseException]]] = [
    ("velocity-mm-per-s-read-as-m-per-s", _v(1e3), 2),
    ("velocity-cm-per-s-read-as-m-per-s", _v(1e2), 2),
    ("velocity-sign-reversed", _v(-1.0), 2),
    ("velocity-mm-per-s-and-sign-reversed", _v(-1e3), 2),
    ("velocity-half-scale", _v(0.5), 2),
    ("velocity-scale-1.4", _v(1.4), 2),
    ("velocity-noise-channel", _velocity_noise, 2),
    ("velocity-header-m-per-s-values-mm-per-s",
     _v(1e3, header="time,displacement,force,velocity [m/s]"), 2),
    ("velocity-header-in-per-s", _v(1.0, header="time,displacement,force,velocity [in/s]"), 2),
    ("velocity-gzipped-mm-per-s", _velocity_gz, 2),
    ("velocity-in-memory-record-mm-per-s", _velocity_in_memory, DataError),
    ("temperature-looks-like-kelvin", _t(KELVIN), 2),
    ("temperature-header-K", _t(KELVIN, "time,displacement,force,velocity,temperature [K]"), 2),
    ("temperature-header-kelvin-word",
     _t(KELVIN, "time,displacement,force,velocity,temperature (kelvin)"), 2),
    ("temperature-above-400-degC", _t(HOT), 2),
    ("temperature-below-minus-60-degC", _t(COLD), 2),
    ("temperature-header-degF",
     _t(np.full(ROWS, 70.0), "time,displacement,force,velocity,temperature [degF]"), 2),
    ("temperature-manifest-initial-in-kelvin", _start_in_kelvin, 2),
    ("temperature-in-memory-out-of-range", _temperature_in_memory, DataError),
    ("duplicate-column-force", _header("time,displacement,force,force", "'force'"), 2),
    ("duplicate-column-case-and-space",
     _header("time,displacement,force,velocity, FORCE ", "'FORCE'"), 2),
    ("duplicate-column-with-unit",
     _header("time,displacement [m],force,displacement", "'displacement'"), 2),
    ("duplicate-column-time", _header("time,displacement,force,time", "'time'"), 2),
    ("duplicate-column-in-a-manifest-test", _duplicate_in_manifest, 2),
    ("header-unit-force-kN", _header("time,displacement,force [kN],velocity", "'force'",
                                     "'kN'"), 2),
    ("header-unit-time-ms", _header("time [ms],displacement,force,velocity", "'time'",
                                    "'ms'"), 2),
    ("header-unit-displacement-mm", _header("time,displacement (mm),force,velocity",
                                            "'displacement'", "'mm'"), 2),
    ("header-unit-axial-force-kN",
     _header("time,displacement,force,velocity,axial_force [kN]", "'axial_force'"), 2),
    ("header-rows-wider-than-the-header", _wide, 2),
    ("manifest-radius-disagrees-with-flag", _toml("--effective-radius", "effective_radius",
                                                  "3.5"), 2),
    ("manifest-diameter-disagrees-with-flag", _toml("--slider-diameter", "slider_diameter",
                                                    "0.25"), 2),
    ("manifest-toml-axial-load-disagrees-with-flag", _toml("--axial-load", "axial_load",
                                                           "1000000.0"), 2),
    ("manifest-csv-axial-load-disagrees-with-flag", _csv_manifest_second_row, 2),
    ("manifest-api-must-agree-radius", _manifest_api, DataError),
    ("size-sparse-1-GB-csv", _size_sparse, 2),
    ("size-gzipped-2.5-million-rows", _size_gz, 2),
    ("size-max-rows-below-the-file", _max_rows("100"), 2),
    ("size-max-rows-zero", _max_rows("0"), 2),
    ("size-max-rows-negative", _max_rows("-5"), 2),
    ("size-past-the-memory-available", _size_memory, 2),
    ("size-manifest-test-too-large", _size_manifest, 2),
    ("size-api-max-rows-a-string", _size_api_type, InputTypeError),
    ("size-api-campaign-second-file-too-large", _size_api_campaign, DataError),
]


def _hashes(folder: Path) -> dict[str, str]:
    """Content hash of every file under ``folder`` (a sparse file by size and first MB)."""
    out = {}
    for path in sorted(p for p in folder.rglob("*") if p.is_file()):
        with path.open("rb") as handle:
            head = handle.read(1 << 20)
        size = path.stat().st_size
        out[str(path)] = f"{size}:{hashlib.sha256(head).hexdigest()}"
    return out


@pytest.mark.parametrize("build, expected", [pytest.param(b, e, id=i) for i, b, e in CASES])
def test_panel(tmp_path, capsys, monkeypatch, build, expected):
    monkeypatch.setattr(data, "available_memory", getattr(data, "available_memory", None),
                        raising=False)  # restored after the case
    (tmp_path / "earlier_output.json").write_text('{"verdict": ["none"]}\n')
    call, names = build(tmp_path)
    before = _hashes(tmp_path)
    if isinstance(call, list):
        status = main(call)
        message = capsys.readouterr().err
        assert status == expected, message
        assert message.startswith("dcfpb diagnose: error: ") and message.count("\n") == 1
    else:
        with pytest.raises(expected) as caught:
            call()
        assert isinstance(caught.value, InputError)
        message = str(caught.value)
    for name in names:
        assert name in message, (name, message)
    assert _hashes(tmp_path) == before


def test_the_panel_holds_at_least_thirty_cases():
    assert len(CASES) >= 30 and len({c[0] for c in CASES}) == len(CASES)
