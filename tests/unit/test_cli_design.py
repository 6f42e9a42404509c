"""``dcfpb design`` on the command line: the refusal of a suite of 4 pairs (exit status 2,
naming 17.3.2) before any run, the flags' errors naming the flag, ``--overwrite``, and a
complete run writing the report (against a stand-in for :func:`structures.design.design`
returning the helper's DesignResult, so the test stays fast)."""

from __future__ import annotations

import json

import pytest

import structures.design
from dcfpb.cli import main
from dcfpb.common.errors import InputError
from tests.unit.design_result_helper import BUILDING, make_result

pytest.importorskip("matplotlib")


def _manifest(folder, n: int = 4):
    """A pair manifest of ``n`` pairs of tiny text records (never read by the stand-in)."""
    lines = ["name,x,y,dt,units"]
    for k in range(n):
        for role in ("x", "y"):
            (folder / f"p{k}-{role}.txt").write_text("0.0\n0.1\n-0.1\n0.0\n")
        lines.append(f"pair{k},p{k}-x.txt,p{k}-y.txt,0.01,m/s^2")
    path = folder / "pairs.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def calls(monkeypatch):
    """Replace the analysis: refuse fewer than 7 pairs as the real one does, else return the
    helper's result; the calls' arguments are kept."""
    seen = []
    result = make_result()

    def fake(config, pairs, site=None, lambda_=None, **options):
        seen.append({"config": config, "pairs": pairs, "site": site, "lambda_": lambda_,
                     **options})
        n = len(pairs) + (max(0, 7 - len(pairs)) if options.get("complete_with_synthetic")
                          is True else int(options.get("complete_with_synthetic") or 0))
        if n < 7 and not options.get("allow_fewer"):
            raise InputError(f"ASCE/SEI 7-16 17.3.2 asks for at least 7 pairs of ground "
                             f"motions; the suite has {n}.")
        return result

    monkeypatch.setattr(structures.design, "design", fake, raising=False)
    return seen


BASE = ["--site", "1.5,0.6,8", "--lambda", "1.8,0.6", "--R", "2", "--no-progress"]


def test_four_pairs_are_refused_naming_the_rule(tmp_path, capsys, calls):
    manifest = _manifest(tmp_path)
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 2
    assert "17.3.2" in err and "7" in err
    assert not (tmp_path / "out" / "report.md").exists()


def test_four_pairs_are_refused_before_the_analysis_starts(tmp_path, capsys, monkeypatch):
    """The real command (no stand-in): the count is checked before structures.design.design
    is called, so nothing runs."""
    import structures.design.response as response

    def never(*args, **kwargs):
        raise AssertionError("the analysis started")

    monkeypatch.setattr(response, "_run_positions", never)
    manifest = _manifest(tmp_path)
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert status == 2
    assert "ASCE/SEI 7-16 17.3.2 asks for at least 7 pairs" in err
    assert "--synthetic" in err and "--allow-fewer" in err
    assert not (tmp_path / "out").exists()


def test_allow_fewer_reaches_the_analysis(tmp_path, calls):
    manifest = _manifest(tmp_path)
    assert main(["design", str(BUILDING), "--pairs", str(manifest), *BASE, "--allow-fewer",
                 "--out", str(tmp_path / "out")]) == 0
    assert calls[0]["allow_fewer"] is True and len(calls[0]["pairs"]) == 4


def test_a_complete_run_writes_the_report_and_exits_0_with_failed_checks(tmp_path, capsys,
                                                                         calls):
    from dcfpb.report.design import FIGURES, REPORT_FILES

    manifest = _manifest(tmp_path)
    out = tmp_path / "out"
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--synthetic", "auto", "--loads", "follow", "--histories",
                   "--out", str(out)])
    text = capsys.readouterr().out
    assert status == 0
    lines = text.strip().splitlines()
    assert lines[0].startswith("FAIL: 4 of 6 checks passed, 2 failed")
    assert str(out / "report.html") in lines[1]
    for name in (*REPORT_FILES, *FIGURES):
        assert (out / name).is_file(), name
    call = calls[0]
    assert call["complete_with_synthetic"] is True
    assert call["hold_bearing_loads"] is False and call["store"] == "full"
    assert call["site"].S_MS == 1.5 and call["site"].T_L == 8.0
    assert call["lambda_"].lambda_max == pytest.approx(1.8)
    assert call["R"] == 2.0 and call["out_dir"] == out / "runs"
    assert call["positions"] == ("+x", "-x", "+y", "-y")
    report = (out / "report.md").read_text()
    assert "--synthetic auto" in report and "--loads follow" in report
    data = json.loads((out / "design.json").read_text())
    assert {c["key"] for c in data["checks"]} >= {"suite_size", "drift_ratio_x"}

    # the report folder is refused without --overwrite, before any work
    calls.clear()
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--synthetic", "auto", "--out", str(out)])
    err = capsys.readouterr().err
    assert status == 2 and "--out" in err and "--overwrite" in err
    assert calls == []
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--synthetic", "3", "--out", str(out), "--overwrite"])
    assert status == 0 and len(calls) == 1


def test_a_failed_run_exits_1_after_the_report(tmp_path, capsys, monkeypatch):
    result = make_result()
    result.peaks.loc[0, "status"] = "failed"
    monkeypatch.setattr(structures.design, "design", lambda *a, **k: result, raising=False)
    manifest = _manifest(tmp_path, 7)
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--out", str(tmp_path / "out")])
    assert status == 1
    assert "1 of 56 runs did not finish" in capsys.readouterr().out
    assert (tmp_path / "out" / "report.html").is_file()


def test_runs_stopped_at_the_capacity_are_a_design_outcome(tmp_path, capsys, monkeypatch):
    result = make_result()
    result.peaks["failure"] = ""
    result.peaks.loc[[0, 5], ["status", "failure"]] = ["failed", "capacity"]
    monkeypatch.setattr(structures.design, "design", lambda *a, **k: result, raising=False)
    manifest = _manifest(tmp_path, 7)
    status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                   "--out", str(tmp_path / "out")])
    assert status == 0
    assert "2 of 56 runs stopped at the bearings' displacement capacity" in \
        capsys.readouterr().out
    result.peaks.loc[7, ["status", "failure"]] = ["failed", "timeout"]
    assert main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                 "--out", str(tmp_path / "out"), "--overwrite"]) == 1


@pytest.mark.parametrize(("flags", "named"), [
    (["--site", "1.5"], "--site"),
    (["--site", "150,60"], "--site"),
    (["--site", "a,b"], "--site"),
    (["--lambda", "0.6,1.8"], "--lambda"),
    (["--lambda", "1.8"], "--lambda"),
    (["--lambda-factors", "ae_max=1.2,bogus=2"], "--lambda-factors"),
    (["--lambda-factors", "ae_max=x"], "--lambda-factors"),
    (["--R", "0"], "--R"),
    (["--synthetic", "-1"], "--synthetic"),
    (["--synthetic", "many"], "--synthetic"),
    (["--positions", "+z"], "--positions"),
    (["--positions", "+x,+x"], "--positions"),
    (["--workers", "1", "--scheduler", "tcp://127.0.0.1:1"], "--scheduler"),
])
def test_bad_flags_exit_2_naming_the_flag(tmp_path, capsys, calls, flags, named):
    manifest = _manifest(tmp_path, 7)
    argv = ["design", str(BUILDING), "--pairs", str(manifest), "--site", "1.5,0.6",
            "--lambda", "1.8,0.6", "--R", "2", "--out", str(tmp_path / "out")]
    for flag, value in zip(flags[::2], flags[1::2], strict=True):
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        elif flag == "--lambda-factors":
            i = argv.index("--lambda")
            argv[i:i + 2] = [flag, value]
        else:
            argv += [flag, value]
    status = main(argv)
    assert status == 2
    assert named in capsys.readouterr().err
    assert calls == []


def test_what_neither_flag_nor_file_gives_is_asked_for_by_its_flag(tmp_path, capsys, calls):
    manifest = _manifest(tmp_path, 7)
    for drop, flag in (("--site", "--site"), ("--lambda", "--lambda"), ("--R", "--R")):
        argv = ["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                "--out", str(tmp_path / "out")]
        i = argv.index(drop)
        del argv[i:i + 2]
        assert main(argv) == 2
        assert f"{flag} " in capsys.readouterr().err
    assert calls == []


def test_unused_flags_warn(tmp_path, capsys, calls):
    from dcfpb.common.errors import InputWarning

    manifest = _manifest(tmp_path, 7)
    with pytest.warns(InputWarning) as caught:
        status = main(["design", str(BUILDING), "--pairs", str(manifest), *BASE,
                       "--allow-fewer", "--synthetic", "auto", "--out", str(tmp_path / "out")])
    assert status == 0
    messages = [str(w.message) for w in caught]
    assert any(m.startswith("--allow-fewer has no effect") for m in messages)
    assert any(m.startswith("--synthetic auto has no effect") for m in messages)


def test_a_building_without_a_plan_is_refused(tmp_path, capsys, calls):
    manifest = _manifest(tmp_path, 7)
    planar = BUILDING.parent / "five_storey.toml"
    status = main(["design", str(planar), "--pairs", str(manifest), *BASE,
                   "--out", str(tmp_path / "out")])
    assert status == 2 and "[plan]" in capsys.readouterr().err


def test_a_plan_without_dimensions_is_refused(tmp_path, capsys, calls):
    manifest = _manifest(tmp_path, 7)
    text = BUILDING.read_text().replace("dimensions = [24.0, 12.0]", "")
    building = tmp_path / "no_dimensions.toml"
    building.write_text(text)
    status = main(["design", str(building), "--pairs", str(manifest), *BASE,
                   "--out", str(tmp_path / "out")])
    assert status == 2 and "dimensions" in capsys.readouterr().err
    assert calls == []


def test_the_building_files_design_table_stands_in_for_the_flags(tmp_path, calls):
    manifest = _manifest(tmp_path, 7)
    building = tmp_path / "with_design.toml"
    building.write_text(BUILDING.read_text() + "\n[design]\nlambda_max = 1.8\n"
                        "lambda_min = 0.6\nS_MS = 1.5\nS_M1 = 0.6\nR = 2.0\n")
    assert main(["design", str(building), "--pairs", str(manifest), "--no-progress",
                 "--out", str(tmp_path / "out")]) == 0
    assert calls[-1]["site"].S_MS == 1.5 and calls[-1]["lambda_"].lambda_max == 1.8
    assert calls[-1]["R"] == 2.0  # the file's [design], resolved as the analysis does
    assert main(["design", str(building), "--pairs", str(manifest), "--no-progress",
                 "--site", "1.0,0.4", "--out", str(tmp_path / "out2")]) == 0
    assert calls[-1]["site"].S_MS == 1.0  # the flag overrides the file


def test_the_real_analysis_end_to_end_on_two_short_pairs(tmp_path, capsys):
    """No stand-in: structures.design.design on two 4 s synthetic pairs (--allow-fewer), one
    mass position, one worker; the report says the suite is not compliant."""
    from groundmotions import synthetic_pair

    lines = ["name,x,y,dt,units"]
    for k in range(2):
        pair = synthetic_pair("kanai-tajimi", 10 + k, duration=4.0, dt=0.01, target_pga=2.0,
                              ground_frequency=12.0, ground_damping=0.6)
        for role in ("x", "y"):
            values = getattr(pair, role).acceleration
            (tmp_path / f"p{k}-{role}.txt").write_text("\n".join(map(repr, map(float, values))))
        lines.append(f"pair{k},p{k}-x.txt,p{k}-y.txt,0.01,m/s^2")
    (tmp_path / "pairs.csv").write_text("\n".join(lines) + "\n")
    out = tmp_path / "out"
    status = main(["design", str(BUILDING), "--pairs", str(tmp_path / "pairs.csv"), *BASE,
                   "--allow-fewer", "--positions", "+x", "--workers", "1", "--out", str(out)])
    text = capsys.readouterr().out
    assert status == 0, text
    assert "suite NOT COMPLIANT with 17.3.2" in text.splitlines()[0]
    report = (out / "report.md").read_text()
    assert "NOT COMPLIANT" in report
    data = json.loads((out / "design.json").read_text())
    assert data["compliant_suite"] is False and data["passed"] is False
    suite = next(c for c in data["checks"] if c["key"] == "suite_size")
    assert suite["clause"] == "17.3.2" and suite["passed"] is False
    for check in data["checks"]:
        assert f"| {check['key']} |" in report
    assert len(data["figures"]) == 6 and (out / "runs").is_dir()
