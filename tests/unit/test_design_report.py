"""The report of ``dcfpb design`` (:mod:`dcfpb.report.design`) on a DesignResult of the contract
(:mod:`structures.design.result`) built by ``design_result_helper``: every file, every check row
in both documents with PASS or FAIL, design.json with every check key, relative links only, and
what the report says when the governing run or its floor spectra are absent."""

from __future__ import annotations

import json
import re
from html.parser import HTMLParser
from urllib.parse import urlsplit

import pandas as pd
import pytest

from tests.unit.design_result_helper import make_result

pytest.importorskip("matplotlib")


@pytest.fixture(scope="module")
def result():
    return make_result()


@pytest.fixture(scope="module")
def report(result, tmp_path_factory):
    from dcfpb.report.design import write_report

    folder = tmp_path_factory.mktemp("design-report")
    written = write_report(result, folder, command="dcfpb design b.toml --pairs p.csv")
    return folder, written


def test_every_file_is_written(report):
    from dcfpb.report.design import FIGURES, REPORT_FILES

    folder, written = report
    for name in (*REPORT_FILES, *FIGURES):
        assert (folder / name).is_file(), name
        assert (folder / name).stat().st_size > 0, name
        assert written[name] == folder / name
    for name in FIGURES:
        assert (folder / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", name
    assert not list(folder.glob(".*.tmp"))


def _check_rows(text: str, result) -> None:
    for check in result.checks:
        line = next((row for row in text.splitlines() if f"| {check.key} |" in row), None)
        assert line is not None, check.key
        assert check.clause in line
        if check.kind == "floor":  # a floor on the design value says which governs
            assert ("FLOOR GOVERNS" if check.floor_governs else "RH GOVERNS") in line
        else:
            assert ("PASS" if check.passed else "FAIL") in line


def test_every_check_is_one_row_with_its_clause_and_verdict(report, result):
    folder, _ = report
    markdown = (folder / "report.md").read_text()
    _check_rows(markdown, result)
    page = (folder / "report.html").read_text()
    rows = re.findall(r"<tr>.*?</tr>", page, re.S)
    for check in result.checks:
        row = next(r for r in rows if re.search(rf"<td[^>]*>{check.key}</td>", r))
        assert re.search(rf"<td[^>]*>{re.escape(check.clause)}</td>", row)
        verdict = "pass" if check.passed else "fail"
        assert f'<td class="{verdict}">{verdict.upper()}</td>' in row
        assert re.search(r'<td class="num">[+-]?(\d+\.\d %|inf \(limit 0\))</td></tr>', row)
    assert any(not c.passed for c in result.checks)  # the helper has a failing check
    assert "**FAIL**" in markdown.splitlines()[2]


def test_the_two_documents_hold_the_same_tables(report):
    folder, _ = report
    markdown = (folder / "report.md").read_text()
    page = (folder / "report.html").read_text()
    titles = re.findall(r"^\*\*(.+)\*\*$", markdown, re.M)
    assert len(titles) >= 8
    for title in titles:
        assert title.replace("&", "&amp;").replace("'", "&#x27;") in page, title
    for clause in ("17.6.4.4", "17.3.2", "17.5.3.3", "Table 17.5-1"):
        assert clause in markdown and clause in page


def test_design_json_holds_every_check_and_number(report, result):
    folder, _ = report
    data = json.loads((folder / "design.json").read_text())
    keys = {c["key"] for c in data["checks"]}
    assert keys == {c.key for c in result.checks}
    for entry in data["checks"]:
        assert {"clause", "demand", "limit", "unit", "passed", "margin"} <= set(entry)
    assert data["figures"] == ["spectra.png", "displacements.png", "orbit.png",
                               "hysteresis.png", "drift_ratios.png", "floor_spectra.png"]
    assert data["elf"]["bounds"]["lower"]["D_M"]["unit"] == "m"
    assert data["passed"] is False


def test_peaks_csv_is_the_peaks_table(report, result):
    folder, _ = report
    peaks = pd.read_csv(folder / "peaks.csv")
    assert len(peaks) == len(result.peaks)
    assert list(peaks.columns) == list(result.peaks.columns)


class _Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links = []

    def handle_starttag(self, tag, attrs):
        self.links += [value for name, value in attrs if name in ("href", "src")]


def test_links_are_relative_and_resolve(report):
    folder, _ = report
    parser = _Links()
    parser.feed((folder / "report.html").read_text())
    assert parser.links
    for link in parser.links:
        parts = urlsplit(link)
        assert not parts.scheme and not parts.netloc and not link.startswith("/"), link
        if parts.path:
            assert (folder / parts.path).is_file(), link
    markdown = (folder / "report.md").read_text()
    for link in re.findall(r"\]\(([^)]+)\)", markdown):
        assert not urlsplit(link).scheme and (folder / link).is_file(), link


def test_without_governing_run_or_floor_spectra_the_report_says_so(tmp_path):
    from dcfpb.report.design import write_report

    write_report(make_result(governing=False, compliant=False), tmp_path / "none")
    text = (tmp_path / "none" / "report.md").read_text()
    assert "No governing run was kept" in text
    assert "NOT COMPLIANT" in text
    for name in ("orbit.png", "hysteresis.png", "floor_spectra.png"):
        assert not (tmp_path / "none" / name).exists()
        assert name not in text
    write_report(make_result(floor_spectra=False), tmp_path / "nofloor")
    text = (tmp_path / "nofloor" / "report.md").read_text()
    assert "holds no floor spectra" in text
    assert (tmp_path / "nofloor" / "orbit.png").is_file()
    assert not (tmp_path / "nofloor" / "floor_spectra.png").exists()
