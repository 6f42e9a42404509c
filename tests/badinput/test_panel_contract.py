"""The bad-input panel of the failure contract (issue 22, part 5): one call per case.

Each case is one call of the command line (``dcfpb.cli.main`` in-process) or of the public Python
API, and asserts (a) the exit status (2 bad input, 1 run failure, 3 internal error) or the
exception class, (b) that the message names the argument, flag, key or file concerned and (c)
that no input file and no earlier output in the case's folder changed (every file hashed before
and after; the inputs are copies in ``tmp_path``). Ids name the kind of each case.
"""

from __future__ import annotations

import hashlib
import socket
import threading
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from dcfpb.cli import main
from dcfpb.common.errors import InputError, InputTypeError

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "five_storey.toml"
RECORD = REPO / "groundmotions" / "data" / "elcentro_1940_ns.at2"


@dataclass
class Inputs:
    """The copies a case works on, in its own folder, and the earlier outputs beside them."""

    folder: Path
    building: Path
    record: Path
    records: Path
    out: Path
    earlier: Path

    def snapshot(self) -> dict[str, str]:
        return {str(p.relative_to(self.folder)): hashlib.sha256(p.read_bytes()).hexdigest()
                for p in sorted(self.folder.rglob("*")) if p.is_file()}


@pytest.fixture
def inputs(tmp_path, tmp_path_factory, monkeypatch) -> Inputs:
    monkeypatch.setenv("DCFPB_LOG_DIR", str(tmp_path_factory.mktemp("logs")))
    records = tmp_path / "records"
    records.mkdir()
    record = records / RECORD.name
    record.write_bytes(RECORD.read_bytes())
    building = tmp_path / EXAMPLE.name
    building.write_bytes(EXAMPLE.read_bytes())
    out = tmp_path / "suite-out"
    out.mkdir()
    earlier = out / "peaks.csv"
    earlier.write_text("run_id,peak\nearlier,1.0\n")
    return Inputs(tmp_path, building, record, records, out, earlier)


def _suite(i: Inputs) -> list[str]:
    """A suite into the folder of an earlier output, allowed to replace it: each case reaches
    the check it is about, and the earlier output must stay whole all the same."""
    return ["suite", str(i.building), "--records", str(i.records), "--out", str(i.out),
            "--overwrite"]


def _closed_port(_: Inputs) -> str:
    probe = socket.socket()
    probe.bind(("127.0.0.1", 0))
    port = probe.getsockname()[1]
    probe.close()
    return f"tcp://127.0.0.1:{port}"


def _garbage_server(_: Inputs) -> str:
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()

    def serve():
        conn, _ = server.accept()
        conn.sendall(b"\x13\x37" * 2048)
        conn.close()
        server.close()

    threading.Thread(target=serve, daemon=True).start()
    return f"tcp://127.0.0.1:{server.getsockname()[1]}"


@dataclass
class Case:
    """A call (``argv`` of the command line, or ``api`` of the Python API) on the inputs, the
    expected status or exception class, and the names the message must hold."""

    call: Callable[[Inputs], list[str]] | Callable[[Inputs], object]
    expected: int | type[BaseException]
    names: tuple[str, ...]
    cli: bool = True


def _api(call: Callable[[Inputs], object], names: str | tuple[str, ...],
         expected: type[BaseException] = InputTypeError) -> Case:
    return Case(call, expected, (names,) if isinstance(names, str) else names, cli=False)


def _cli(argv: Callable[[Inputs], list[str]], status: int, *names: str) -> Case:
    return Case(argv, status, names)


def _gm():
    import groundmotions

    return groundmotions


def _iso():
    import isolator

    return isolator


def _st():
    import structures

    return structures


def _elcentro():
    return _gm().load_bundled("elcentro")


def _config(i: Inputs):
    return _st().load_config(i.building)


def _bearing():
    return _iso().protocol_bearing("constant")


def _suites():
    import structures.suites as suites

    return suites


def _first_step_building(i: Inputs) -> Path:
    text = i.building.read_text().replace("yield_displacement = 0.0005",
                                          "yield_displacement = 1e-12")
    path = i.folder / "first_step.toml"
    path.write_text(text)
    return path


def _short_record(i: Inputs) -> Path:
    path = i.folder / "short.txt"
    np.savetxt(path, _elcentro().acceleration[:40] / 9.80665)
    return path


PERIODS = np.array([0.5, 1.0])

CASES: dict[str, Case] = {
    # the Python API with an argument of the wrong kind: InputTypeError naming it
    "api-type-read-record-path-int": _api(lambda i: _gm().read_record(123), "'path'"),
    "api-type-read-record-path-list": _api(lambda i: _gm().read_record([str(i.record)]),
                                           "'path'"),
    "api-type-read-pair-x-path-int": _api(lambda i: _gm().read_pair(1, i.record), "'x_path'"),
    "api-type-spectrum-motion-str": _api(lambda i: _gm().spectrum(str(i.record), PERIODS),
                                         "'motion'"),
    "api-type-spectrum-periods-str": _api(lambda i: _gm().spectrum(_elcentro(), "0.5,1"),
                                          "'periods'"),
    "api-type-response-spectrum-acceleration-str": _api(
        lambda i: _gm().response_spectrum("abc", 0.01, PERIODS), "'acceleration'"),
    "api-type-groundmotion-acceleration-str": _api(
        lambda i: _gm().GroundMotion("abc", 0.01), "'acceleration'"),
    "api-type-scale-suite-motions-str": _api(
        lambda i: _gm().scale_suite(str(i.record), _gm().asce7_design_spectrum(1.0, 0.6, 8.0),
                                    (1.0, 2.0)), "'motions'"),
    "api-type-suite-spectra-motions-str": _api(
        lambda i: _gm().suite_spectra(str(i.record), PERIODS), "'motions'"),
    "api-type-run-test-bearing-str": _api(
        lambda i: _iso().run_test("constant", [0.0, 1.0], [0.0, 0.1]), "'bearing'"),
    "api-type-run-test-time-str": _api(
        lambda i: _iso().run_test(_bearing(), "0,1", [0.0, 0.1]), "'time'"),
    "api-type-run-orbit-orbit-str": _api(lambda i: _iso().run_orbit(_bearing(), "circle"),
                                         "'orbit'"),
    "api-type-sine-amplitude-str": _api(lambda i: _iso().sine("0.1", 2.0, 1, 0.01),
                                        "'amplitude'"),
    "api-type-friction-model-int": _api(
        lambda i: _iso().friction_model(1, slider_diameter=0.3, design_pressure=60e6,
                                        design_velocity=0.4), "'model'"),
    "api-type-cycle-characteristics-displacement-str": _api(
        lambda i: _iso().cycle_characteristics("abc", [1.0, 2.0]), "'displacement'"),
    "api-type-structures-run-config-int": _api(lambda i: _st().run(5, _elcentro()), "'config'"),
    "api-type-structures-run-motion-list": _api(
        lambda i: _st().run(i.building, [_elcentro()]), "'motion'"),
    "api-type-structures-run-dt-str": _api(lambda i: _st().run(i.building, _elcentro(),
                                                               dt="0.01"), "'dt'"),
    "api-type-structures-run-integrator-int": _api(
        lambda i: _st().run(i.building, _elcentro(), integrator=2), "'integrator'"),
    "api-type-run-building-bearing-str": _api(
        lambda i: _st().run_building(_config(i).building, "constant", _elcentro()),
        "'bearing'"),
    "api-type-run-fixed-base-building-str": _api(
        lambda i: _st().run_fixed_base(str(i.building), _elcentro()), "'building'"),
    "api-type-load-config-path-int": _api(lambda i: _st().load_config(5), "'path'"),
    "api-type-peaks-result-str": _api(lambda i: _st().peaks("result.nc"), "'result'"),
    "api-type-with-floor-spectra-result-str": _api(
        lambda i: _st().with_floor_spectra("result.nc"), "'result'"),
    "api-type-ratios-result-str": _api(
        lambda i: _st().ratios_to_fixed_base("a.nc", "b.nc"), "'result'"),
    "api-type-default-step-str": _api(lambda i: _st().default_step("0.02"), "'record_dt'"),
    "api-type-suite-config-path": _api(
        lambda i: _suites().Suite(str(i.building), [i.record]), "'config'"),
    "api-type-suite-models-int": _api(
        lambda i: _suites().Suite(_config(i), [i.record], models=3), "'models'"),
    "api-type-run-suite-suite-str": _api(
        lambda i: _suites().run_suite("suite", i.out, progress=False), "'suite'"),
    "api-scheduler-address-int": _api(
        lambda i: __import__("structures.suites.tasks", fromlist=["x"]).check_scheduler(8786),
        "scheduler_address"),
    "api-workers-zero": _api(
        lambda i: __import__("structures.suites.tasks", fromlist=["x"]).capped_workers(0),
        "'n_workers'", InputError),
    # the command line: bad input exits 2 naming the flag or file, before any work
    "cli-scheduler-closed-port": _cli(
        lambda i: [*_suite(i), "--scheduler", _closed_port(i)], 2, "--scheduler", "cannot connect"),
    "cli-scheduler-garbage-server": _cli(
        lambda i: [*_suite(i), "--scheduler", _garbage_server(i)], 2, "--scheduler",
        "not a Dask scheduler"),
    "cli-scheduler-no-port": _cli(
        lambda i: [*_suite(i), "--scheduler", "tcp://127.0.0.1"], 2, "--scheduler", "tcp://127.0.0.1"),
    "cli-scheduler-unknown-scheme": _cli(
        lambda i: [*_suite(i), "--scheduler", "http://127.0.0.1:8786"], 2, "--scheduler", "http"),
    "cli-scheduler-empty": _cli(
        lambda i: [*_suite(i), "--scheduler", ""], 2, "--scheduler"),
    "cli-workers-zero": _cli(
        lambda i: [*_suite(i), "--workers", "0"], 2, "'--workers'", "[1, inf)"),
    "cli-workers-and-scheduler": _cli(
        lambda i: [*_suite(i), "--workers", "1", "--scheduler", "tcp://127.0.0.1:1"], 2,
        "--workers", "--scheduler"),
    "cli-path-record-is-a-folder": _cli(
        lambda i: ["run", str(i.building), "--record", str(i.records)], 2, "--record",
        "records"),
    "cli-path-record-missing": _cli(
        lambda i: ["run", str(i.building), "--record", str(i.folder / "gone.at2")], 2,
        "gone.at2"),
    "cli-path-spectrum-record-is-a-folder": _cli(
        lambda i: ["spectrum", str(i.records)], 2, "record", "records"),
    "cli-path-building-is-a-folder": _cli(
        lambda i: ["run", str(i.records), "--record", str(i.record)], 2, "records"),
    "cli-path-suite-records-missing": _cli(
        lambda i: ["suite", str(i.building), "--records", str(i.folder / "none"), "--out",
                   str(i.out), "--overwrite"], 2, "none"),
    # a run with good input that fails at its first step: exit 1 with its time and cause
    "cli-run-fails-at-first-step": _cli(
        lambda i: ["run", str(_first_step_building(i)), "--record", str(_short_record(i)),
                   "--record-dt", "0.02", "--units", "g", "--json"], 1,
        "run failed (convergence) at t = 0.005 s", "Step 1"),
}


def _internal(i: Inputs) -> list[str]:
    return ["protocol", "--model", "constant"]


INTERNAL = "cli-internal-error-bare-value-error"


@pytest.mark.parametrize("case", [*CASES, INTERNAL], ids=[*CASES, INTERNAL])
def test_panel(case, inputs, capsys, monkeypatch):
    before = inputs.snapshot()
    if case == INTERNAL:
        import dcfpb.cli.protocol as protocol

        def broken(args):
            raise ValueError("a bare ValueError from a handler")

        monkeypatch.setattr(protocol, "_run_protocol", broken)
        spec = _cli(_internal, 3, "internal error", "ValueError", "with the log",
                    "a bare ValueError from a handler")
    else:
        spec = CASES[case]
    if spec.cli:
        argv = spec.call(inputs)
        before = inputs.snapshot()  # the case's own inputs written
        status = main(argv)
        err = capsys.readouterr().err
        assert status == spec.expected, err
        message = err
    else:
        with pytest.raises(spec.expected) as caught:
            spec.call(inputs)
        message = str(caught.value)
    for name in spec.names:
        assert name in message, (name, message)
    assert inputs.snapshot() == before
