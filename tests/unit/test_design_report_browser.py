"""The design report's HTML in a real browser: ``tools/check_report_html.py`` loads a report the
tests write in headless Chromium and finds every image decoded and no link broken; a broken
report is caught. Skipped where ``/usr/bin/chromium`` is absent (CI machines have none)."""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

import pytest

from tests.unit.design_result_helper import make_result

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = Path("/usr/bin/chromium")

pytestmark = pytest.mark.skipif(not CHROMIUM.is_file(),
                                reason="/usr/bin/chromium is absent (apt-get install -y "
                                "chromium): the browser check needs a real Chromium")


def _checker():
    spec = importlib.util.spec_from_file_location("check_report_html",
                                                  ROOT / "tools" / "check_report_html.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    pytest.importorskip("matplotlib")
    from dcfpb.report.design import write_report

    folder = tmp_path_factory.mktemp("browser-report")
    write_report(make_result(), folder)
    return folder


def test_the_report_loads_with_every_figure_and_link(report, tmp_path, capsys):
    checker = _checker()
    shot = tmp_path / "report.png"
    assert checker.main([str(report), "--chromium", str(CHROMIUM),
                         "--screenshot", str(shot)]) == 0
    out = capsys.readouterr().out
    assert "OK:" in out and "6 of 6 images decoded" in out
    assert shot.read_bytes()[:4] == b"\x89PNG"


def test_a_broken_report_is_caught(report, tmp_path, capsys):
    broken = tmp_path / "broken"
    shutil.copytree(report, broken)
    (broken / "orbit.png").write_bytes(b"not a png")
    page = (broken / "report.html").read_text()
    (broken / "report.html").write_text(page.replace('href="#checks"', 'href="#missing"', 1)
                                        .replace("</body>", '<a href="/etc/passwd">x</a>'
                                                 "</body>"))
    checker = _checker()
    assert checker.main([str(broken), "--chromium", str(CHROMIUM)]) == 1
    out = capsys.readouterr().out
    assert "<img src='orbit.png'> not decoded" in out
    assert "'#missing'" in out
    assert "'/etc/passwd' is not a relative link" in out
