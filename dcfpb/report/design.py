"""The report of a Chapter 17 design analysis (``dcfpb design``): one folder with

- ``report.md`` and ``report.html``: the same document (the HTML self-contained apart from the
  PNG files beside it, linked relatively, with a small inline style sheet);
- ``design.json``: :meth:`~structures.design.result.DesignResult.to_dict` (every number of the
  report, keyed, SI units) with the list of the figures and files written;
- ``peaks.csv``: the peaks of every run (:attr:`~structures.design.result.DesignResult.peaks`);
- the figures of :mod:`dcfpb.plotting.design` (:data:`FIGURES`).

The document is built once as a list of blocks (headings, paragraphs, lists, tables, figures)
and rendered twice, so the two forms cannot differ in content. Numbers are shown in SI units as
stored, forces in kN (design.json keeps N); every check is one row with its clause, demand,
limit, unit, PASS or FAIL and the margin in %. The report computes nothing of its own: it renders
the result objects and the table of the standard's limits
(:data:`structures.design.limits.LIMITS`).
"""

from __future__ import annotations

import contextlib
import html
import json
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from dcfpb.common.files import json_safe

__all__ = ["FIGURES", "REPORT_FILES", "Block", "build_document", "render_html",
           "render_markdown", "report_files", "write_report"]

REPORT_FILES = ("report.md", "report.html", "design.json", "peaks.csv")
"""The report's documents and data, always written."""

FIGURES = ("spectra.png", "displacements.png", "orbit.png", "hysteresis.png",
           "drift_ratios.png", "floor_spectra.png")
"""The figures, written where their data exist (the last four need the governing run, the
last its floor spectra)."""

_DISPLAY_UNITS = {"N": ("kN", 1e-3), "N/m": ("kN/m", 1e-3), "J": ("kJ", 1e-3)}
"""Units shown scaled in the documents (design.json and peaks.csv keep SI)."""


def report_files() -> tuple[str, ...]:
    """Every file name the report may write in its folder (for the output checks)."""
    return (*REPORT_FILES, *FIGURES)


# --- the document ------------------------------------------------------------------------------

@dataclass(frozen=True)
class Block:
    """One block of the document.

    ``kind`` is ``"heading"`` (``text``, ``level``, ``anchor``), ``"paragraph"`` (``text``),
    ``"list"`` (``items``), ``"table"`` (``title``, ``header``, ``rows`` of text cells,
    ``note``, ``status`` the index of a PASS/FAIL column or -1) or ``"figure"`` (``file``,
    ``text`` the caption).
    """

    kind: str
    text: str = ""
    level: int = 2
    anchor: str = ""
    items: tuple[str, ...] = ()
    title: str = ""
    header: tuple[str, ...] = ()
    rows: tuple[tuple[str, ...], ...] = ()
    note: str = ""
    status: int = -1
    file: str = ""


def _heading(text: str, anchor: str, level: int = 2) -> Block:
    return Block("heading", text=text, level=level, anchor=anchor)


def _paragraph(text: str) -> Block:
    return Block("paragraph", text=text)


def _list(items: Sequence[str]) -> Block:
    return Block("list", items=tuple(items))


def _table(title: str, header: Sequence[str], rows: Sequence[Sequence[str]], note: str = "",
           status: int = -1) -> Block:
    return Block("table", title=title, header=tuple(header),
                 rows=tuple(tuple(r) for r in rows), note=note, status=status)


def _figure(file: str, caption: str) -> Block:
    return Block("figure", file=file, text=caption)


# --- formatting --------------------------------------------------------------------------------

def _unit(unit: str) -> tuple[str, float]:
    """The unit shown and the factor from the stored (SI) one."""
    return _DISPLAY_UNITS.get(unit, (unit, 1.0))


def _fmt(value: Any, unit: str = "") -> str:
    """A cell: numbers with 4 significant digits (scaled to the shown unit), booleans as
    yes/no, None and NaN as a dash."""
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if hasattr(value, "item") and not isinstance(value, str | bytes):
        with contextlib.suppress(ValueError, AttributeError):
            value = value.item()
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return "-" if math.isnan(value) else ("inf" if value > 0 else "-inf")
        value *= _unit(unit)[1]
        if value == 0:
            return "0"
        if abs(value) >= 1e5 or abs(value) < 1e-3:
            return f"{value:.4g}"
        return f"{value:.4g}" if abs(value) < 1e4 else f"{value:.0f}"
    if isinstance(value, list | tuple):
        return ", ".join(_fmt(v, unit) for v in value)
    return str(value)


def _with_unit(name: str, unit: str) -> str:
    shown = _unit(unit)[0]
    return f"{name} [{shown}]" if shown else name


def _percent(value: float) -> str:
    if value is None or not math.isfinite(value):
        if value is None or math.isnan(value):
            return "-"
        return "+inf (limit 0)" if value > 0 else "-inf (limit 0)"
    shown = round(100.0 * value, 1)
    return "0.0 %" if shown == 0 else f"{shown:+.1f} %"


# --- the parts of the document -----------------------------------------------------------------

def _summary(result: Any) -> list[Block]:
    checks = list(result.checks)
    failed = [c for c in checks if not c.passed]
    verdict = "PASS" if result.passed else "FAIL"
    line = (f"**{verdict}**: {len(checks) - len(failed)} of {len(checks)} checks pass"
            + (f", {len(failed)} fail ({', '.join(c.key for c in failed)})" if failed else ""))
    if not result.compliant_suite:
        line += "; the suite of ground motions is NOT COMPLIANT with 17.3.2"
    return [_paragraph(line + ".")]


def _analysis(result: Any, command: str | None) -> list[Block]:
    options = dict(result.options or {})
    elf = result.elf
    items = [f"building: {result.name}"]
    site = elf.site
    items.append(f"site (MCE_R): S_MS = {site.S_MS:g} g, S_M1 = {site.S_M1:g} g, T_L = "
                 + (f"{site.T_L:g} s" if site.T_L is not None else "not given"))
    lam = elf.lambda_
    items.append(f"property modification (17.2.8.4): lambda_max = {lam.lambda_max:.4g}, "
                 f"lambda_min = {lam.lambda_min:.4g}; friction model {elf.model}, nominal "
                 f"mu = {elf.mu_nominal:.4g}")
    items.append(f"R = {elf.R:g}, R_I = {elf.R_I:g}, I_e = {elf.I_e:g}; W = "
                 f"{elf.W / 1e3:.5g} kN on the isolators, W_s = {elf.W_s / 1e3:.5g} kN above")
    real = sum(not p.synthetic for p in result.pairs)
    synthetic = len(result.pairs) - real
    items.append(f"ground motions: {len(result.pairs)} pairs ({real} recorded, {synthetic} "
                 f"synthetic), scaled on RotD100 over {result.spectra.period_range[0]:.3g} to "
                 f"{result.spectra.period_range[1]:.3g} s (17.3.3); suite "
                 + ("compliant" if result.compliant_suite else "NOT COMPLIANT") + " (17.3.2)")
    bounds = ", ".join(dict.fromkeys(str(b) for b in result.peaks["bound"]))
    positions = ", ".join(dict.fromkeys(str(p) for p in result.peaks["position"]))
    items.append(f"runs: {len(result.peaks)} (bounds {bounds}; centre of mass at {positions})"
                 + ("" if "hold_bearing_loads" not in options else
                    "; bearing gravity loads " + ("held at the nominal distribution"
                                                  if options["hold_bearing_loads"] else
                                                  "following the moved masses")))
    if "store" in options:
        items.append(f"storage per run: {options['store']}")
    timings = options.get("timings")
    if isinstance(timings, dict) and "total" in timings:
        items.append(f"analysis wall time: {float(timings['total']):.1f} s")
    if command:
        items.append(f"command: `{command}`")
    return [_heading("The analysis", "analysis"), _list(items)]


def _notes(result: Any) -> list[Block]:
    notes = list(result.notes)
    if not notes:
        return []
    return [_heading("Notes", "notes"), _list(notes)]


def _checks(result: Any) -> list[Block]:
    header = ("clause", "check", "key", "demand", "limit", "unit", "bound, mass at",
              "result", "margin")
    rows = []
    for c in result.checks:
        unit = _unit(c.unit)[0]
        where = ", ".join(x for x in (c.bound, c.position) if x)
        relation = {"max": "≤", "min": "≥", "floor": "floor"}[c.kind]
        if c.kind != "floor":
            verdict = "PASS" if c.passed else "FAIL"
        elif c.floor_governs:
            verdict = f"FLOOR GOVERNS: results x {c.scale_up:.3g}"
        else:
            verdict = "RH GOVERNS"
        rows.append((c.clause, c.description, c.key, _fmt(float(c.demand), c.unit),
                     f"{relation} {_fmt(float(c.limit), c.unit)}", unit or "-", where or "-",
                     verdict, _percent(c.margin)))
    note = ("limit: ≤ the demand may not exceed it, ≥ the demand may not fall below it; floor: "
            "a lower bound on the design value, not a pass/fail test: a response-history (RH) "
            "value below it is raised to it and every response scaled up by the factor shown "
            "(17.6.4.3). margin: (limit - demand) / |limit| for an upper limit, (demand - limit) "
            "/ |limit| for a lower one or a floor; positive passes (a floor: the RH lies above "
            "it). The key names the check in design.json.")
    return [_heading("Checks", "checks"),
            _table("Every check of the standard", header, rows, note, status=7)]


def _result_tables(result: Any) -> list[Block]:
    blocks = [_heading("Results", "results")]
    for table in result.tables:
        columns = list(table.columns)
        units = list(table.units) + [""] * (len(columns) - len(table.units))
        unit_column = columns.index("unit") if "unit" in columns else None
        header = [_with_unit(c, u) for c, u in zip(columns, units, strict=True)]
        rows = []
        for row in table.rows:
            row_unit = str(row[unit_column]) if unit_column is not None else ""
            cells = []
            for i, value in enumerate(row):
                if i == unit_column:
                    cells.append(_unit(str(value))[0] or "-")
                    continue
                unit = units[i] or (row_unit if isinstance(value, float) else "")
                cells.append(_fmt(value, unit))
            rows.append(cells)
        title = f"{table.title} ({table.clause})" if table.clause else table.title
        blocks.append(_table(title, header, rows, table.note))
    return blocks


def _figures(result: Any, figures: dict[str, Path | None]) -> list[Block]:
    blocks = [_heading("Figures", "figures")]
    run = result.governing_run
    elf = result.elf
    captions = {
        "spectra.png": "The RotD100 spectra of the scaled pairs (synthetic ones dashed), their "
        "average and the MCE_R target; the period range of 17.3.3 (0.75 T_M upper bound to "
        "1.25 T_M lower bound) shaded.",
        "displacements.png": "The isolator displacement of every run (the largest resultant "
        "over the bearings) per pair, bound and position of the centre of mass (ringed: the "
        "run stopped at the bearings' displacement capacity), with the ELF's D_M and D_TM of "
        "the bound and the capacity.",
        "orbit.png": "The orbit of the governing run's corner bearing coloured by its contact "
        "temperature, with its displacement capacity and the ELF's D_M and D_TM (lower bound).",
        "hysteresis.png": "The governing run's corner bearing: force against displacement "
        "along x and y.",
        "drift_ratios.png": "The storey drift ratios, averaged over the pairs, per bound and "
        "position of the centre of mass, with the limit of 17.6.4.4 and the ELF's drift "
        "ratios.",
        "floor_spectra.png": "The floor spectra of the governing run (every floor and the "
        "ground).",
    }
    notes: list[Block] = []
    if run is None:
        notes.append(_paragraph("No governing run was kept (the analysis was asked for none): "
                                "the corner bearing's orbit, its hysteresis and the floor "
                                "spectra are not shown."))
    else:
        attrs = run.attrs
        notes.append(_paragraph(
            f"The governing run of the orbit, hysteresis and floor spectra below (the largest "
            f"isolator displacement of the bound and position whose average governs): pair "
            f"{attrs.get('pair', '?')}, "
            f"{attrs.get('bound', '?')} bound, centre of mass at {attrs.get('position', '?')}, "
            f"scale factor {_fmt(attrs.get('scale'))}, property modifier "
            f"{_fmt(attrs.get('property_modifier'))}; ELF D_M = {elf.lower.D_M:.4g} m at the "
            f"lower bound."))
        if not bool(attrs.get("success", True)):
            notes.append(_paragraph(f"The governing run stopped early: "
                                    f"{attrs.get('message') or attrs.get('failure')}"))
        if figures.get("floor_spectra.png") is None:
            notes.append(_paragraph("The governing run holds no floor spectra (not computed): "
                                    "no floor spectra figure."))
    for name in FIGURES:
        if name == "orbit.png":
            blocks += notes
        if figures.get(name) is not None:
            blocks.append(_figure(name, captions[name]))
    return blocks


def _elf(result: Any) -> list[Block]:
    elf = result.elf
    up, low = elf.upper, elf.lower
    from structures.design.elf import CLAUSES, UNITS

    rows = []

    extra = {"lambda": "17.2.8.4", "mu": "17.2.8.4 (lambda mu nominal)",
             "D_TM_over_D_M": "17.5.3.3 (not less than 1.15)", "drift_ratio": "17.5.6"}

    def row(label: str, key: str, a: Any, b: Any) -> None:
        unit = UNITS.get(key, "-")
        rows.append((label, _unit(unit)[0], _fmt(a, unit), _fmt(b, unit),
                     CLAUSES.get(key, extra.get(key, ""))))

    row("lambda", "lambda", up.lambda_, low.lambda_)
    row("mu", "mu", up.mu, low.mu)
    for key in ("K_M", "beta_M", "B_M", "T_M", "D_M"):
        row(key, key, float(getattr(up, key)), float(getattr(low, key)))
    for d in elf.directions:
        row(f"D_TM ({d})", "D_TM", up.directions[d].D_TM, low.directions[d].D_TM)
        row(f"D_TM / D_M ({d})", "D_TM_over_D_M", up.directions[d].D_TM_over_D_M,
            low.directions[d].D_TM_over_D_M)
    for key in ("V_b", "V_st", "V_s_formula", "V_s_fixed_base", "V_s_activation", "V_s_wind",
                "V_s", "F_1"):
        row(key, key, float(getattr(up, key)), float(getattr(low, key)))
    rows.append(("V_s governed by", "", up.V_s_governs, low.V_s_governs, "17.5.4.3"))
    for d in elf.directions:
        row(f"largest drift ratio ({d})", "drift_ratio", up.directions[d].max_drift_ratio,
            low.directions[d].max_drift_ratio)
    blocks = [_heading("The ELF procedure in detail (17.5)", "elf"),
              _table("ELF at the upper and lower bound", ("quantity", "unit", "upper", "lower",
                                                          "clause"), rows,
                     f"{elf.model} model, mu nominal {elf.mu_nominal:.4g}; W = "
                     f"{elf.W / 1e3:.5g} kN, W_s = {elf.W_s / 1e3:.5g} kN")]
    torsion = []
    for bound, result_bound in elf.bounds.items():
        for d, x in result_bound.directions.items():
            torsion.append((bound, d, _fmt(x.y, "m"), _fmt(x.e, "m"), _fmt(x.P_T), _fmt(x.b, "m"),
                            _fmt(x.d, "m"), _fmt(x.torsion_ratio), _fmt(x.D_TM_over_D_M),
                            "yes" if x.floor_governs else "no", _fmt(x.T_fb, "s"), _fmt(x.k)))
    blocks.append(_table("Total maximum displacement with torsion (17.5.3.3, Eq. 17.5-3, "
                         "17.5-4)", ("bound", "direction", "y [m]", "e [m]", "P_T [-]",
                                     "b [m]", "d [m]", "torsion ratio [-]", "D_TM / D_M [-]",
                                     "1.15 floor governs", "T_fb [s]", "k [-]"), torsion))
    for bound, result_bound in elf.bounds.items():
        distribution = []
        for d, x in result_bound.directions.items():
            for k in range(len(x.F)):
                distribution.append((d, str(k + 1), _fmt(float(x.heights[k]), "m"),
                                     _fmt(float(x.F[k]), "N"),
                                     _fmt(float(x.storey_shear[k]), "N"),
                                     _fmt(float(x.drift[k]), "m"),
                                     _fmt(float(x.drift_ratio[k])), _fmt(x.drift_limit)))
        blocks.append(_table(f"Vertical distribution and drift, {bound} bound (17.5.5, 17.5.6)",
                             ("direction", "storey", "height [m]", "F_x [kN]",
                              "storey shear [kN]", "drift [m]", "drift ratio [-]",
                              "limit [-]"), distribution,
                             f"F_1 = {result_bound.F_1 / 1e3:.5g} kN at the base level"))
    if elf.notes:
        blocks.append(_paragraph("Notes of the ELF procedure:"))
        blocks.append(_list(elf.notes))
    return blocks


def _limits() -> list[Block]:
    from structures.design.limits import B_M_TABLE, LIMITS

    rows = [(entry.key, _fmt(float(entry.value)), entry.unit, entry.clause, entry.meaning,
             "yes" if entry.verified else "no", entry.note) for entry in LIMITS.values()]
    return [_heading("The standard's limits used (structures.design.limits)", "limits"),
            _paragraph("Each number the analysis takes from ASCE/SEI 7-16, with its clause, so "
                       "that a reviewer can check it against the text; 'verified' says whether "
                       "it was checked against the text in this package."),
            _table("Limits of ASCE/SEI 7-16 Chapter 17", ("key", "value", "unit", "clause",
                                                          "meaning", "verified", "note"), rows),
            _table("Table 17.5-1: damping coefficient B_M", ("beta_M [-]", "B_M [-]"),
                   [(_fmt(b), _fmt(v)) for b, v in B_M_TABLE],
                   "linear interpolation between the points, held at the ends")]


def _files(figures: dict[str, Path | None]) -> list[Block]:
    items = ["[report.md](report.md) and [report.html](report.html): this report",
             "[design.json](design.json): every number of the report, keyed, in SI units "
             "(N, m, s, degC)",
             "[peaks.csv](peaks.csv): the peaks of every run (pair, bound, position), SI units"]
    items += [f"[{name}]({name})" for name in FIGURES if figures.get(name) is not None]
    return [_heading("Files", "files"), _list(items)]


def build_document(result: Any, figures: dict[str, Path | None], *,
                   command: str | None = None) -> list[Block]:
    """The report as blocks: summary, the analysis, notes, checks, result tables, figures, the
    ELF in detail, the standard's limits and the files (``figures``: name to path, None for one
    not drawn)."""
    blocks = [_heading(f"ASCE/SEI 7-16 Chapter 17 design: {result.name}", "top", level=1)]
    blocks += _summary(result)
    blocks += _analysis(result, command)
    blocks += _notes(result)
    blocks += _checks(result)
    blocks += _result_tables(result)
    blocks += _figures(result, figures)
    blocks += _elf(result)
    blocks += _limits()
    blocks += _files(figures)
    return blocks


# --- rendering ---------------------------------------------------------------------------------

def _md_cell(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def render_markdown(blocks: Sequence[Block]) -> str:
    """The blocks as GitHub-flavoured Markdown."""
    out: list[str] = []
    for block in blocks:
        if block.kind == "heading":
            out += [f"{'#' * block.level} {block.text}", ""]
        elif block.kind == "paragraph":
            out += [block.text, ""]
        elif block.kind == "list":
            out += [f"- {item}" for item in block.items] + [""]
        elif block.kind == "table":
            out += [f"**{block.title}**", ""]
            out.append("| " + " | ".join(_md_cell(h) for h in block.header) + " |")
            out.append("|" + "|".join(" --- " for _ in block.header) + "|")
            for row in block.rows:
                cells = [_md_cell(c) for c in row]
                if 0 <= block.status < len(cells):
                    cells[block.status] = f"**{cells[block.status]}**"
                out.append("| " + " | ".join(cells) + " |")
            out.append("")
            if block.note:
                out += [f"_{block.note}_", ""]
        elif block.kind == "figure":
            out += [f"![{block.text}]({block.file})", "", f"_{block.text}_", ""]
    return "\n".join(out).rstrip() + "\n"


_CSS = """
body { font-family: system-ui, -apple-system, "Segoe UI", sans-serif; margin: 2em auto;
       max-width: 75em; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; border-bottom: 2px solid #444; }
h2 { font-size: 1.3em; border-bottom: 1px solid #bbb; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.5em 0 0.3em 0; font-size: 0.88em; }
h3.table-title { font-size: 0.95em; margin: 1.2em 0 0.2em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.55em; vertical-align: top; }
th { background: #f0f0f0; text-align: left; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
td.short { white-space: nowrap; }
tr:nth-child(even) td { background: #fafafa; }
td.pass { color: #0a6b2b; font-weight: bold; background: #e6f4ea !important; }
td.fail { color: #a50e0e; font-weight: bold; background: #fce8e6 !important; }
p.note { font-size: 0.85em; color: #555; font-style: italic; margin-top: 0; }
figure { margin: 1.5em 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 0.9em; color: #444; }
nav { font-size: 0.9em; }
nav a { margin-right: 1em; }
.verdict-pass { color: #0a6b2b; } .verdict-fail { color: #a50e0e; }
.scroll { overflow-x: auto; }
code { background: #f4f4f4; padding: 0 0.2em; }
"""


def _inline(text: str) -> str:
    """Escaped text with the few Markdown marks the blocks use: **bold**, `code` and
    [label](file) links (relative)."""
    import re

    escaped = html.escape(str(text), quote=True)
    escaped = re.sub(r"\*\*(.+?)\*\*", lambda m: _verdict(m.group(1)), escaped)
    escaped = re.sub(r"`([^`]+)`", r"<code>\1</code>", escaped)
    return re.sub(r"\[([^\]]+)\]\(([^)\s]+)\)", r'<a href="\2">\1</a>', escaped)


def _verdict(text: str) -> str:
    kind = {"PASS": ' class="verdict-pass"', "FAIL": ' class="verdict-fail"'}.get(text, "")
    return f"<strong{kind}>{text}</strong>"


def _is_number(text: str) -> bool:
    try:
        float(str(text).replace(" %", "").replace("+", "").lstrip("≤≥ "))
    except ValueError:
        return str(text) in ("+inf (limit 0)", "-inf (limit 0)")
    return True


def render_html(blocks: Sequence[Block], title: str) -> str:
    """The blocks as one HTML page: inline style sheet, figures linked relatively."""
    body: list[str] = []
    headings = [b for b in blocks if b.kind == "heading" and b.level == 2]
    nav = " ".join(f'<a href="#{b.anchor}">{html.escape(b.text)}</a>' for b in headings)
    for block in blocks:
        if block.kind == "heading":
            anchor = f' id="{block.anchor}"' if block.anchor else ""
            body.append(f"<h{block.level}{anchor}>{html.escape(block.text)}</h{block.level}>")
            if block.level == 1:
                body.append(f"<nav>{nav}</nav>")
        elif block.kind == "paragraph":
            body.append(f"<p>{_inline(block.text)}</p>")
        elif block.kind == "list":
            body.append("<ul>" + "".join(f"<li>{_inline(i)}</li>" for i in block.items)
                        + "</ul>")
        elif block.kind == "table":
            rows = []
            for row in block.rows:
                cells = []
                for i, cell in enumerate(row):
                    if i == block.status:
                        kind = "fail" if cell == "FAIL" else "pass"
                        cells.append(f'<td class="{kind}">{html.escape(cell)}</td>')
                    elif _is_number(cell):
                        cells.append(f'<td class="num">{html.escape(cell)}</td>')
                    elif len(cell) <= 14:
                        cells.append(f'<td class="short">{_inline(cell)}</td>')
                    else:
                        cells.append(f"<td>{_inline(cell)}</td>")
                rows.append("<tr>" + "".join(cells) + "</tr>")
            head = "".join(f"<th>{html.escape(h)}</th>" for h in block.header)
            body.append(f'<h3 class="table-title">{html.escape(block.title)}</h3>')
            body.append(f'<div class="scroll"><table><thead><tr>{head}</tr></thead><tbody>'
                        f"{''.join(rows)}</tbody></table></div>")
            if block.note:
                body.append(f'<p class="note">{_inline(block.note)}</p>')
        elif block.kind == "figure":
            caption = html.escape(block.text)
            body.append(f'<figure><a href="{html.escape(block.file)}"><img src="'
                        f'{html.escape(block.file)}" alt="{caption}"></a>'
                        f"<figcaption>{caption}</figcaption></figure>")
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            f"<title>{html.escape(title)}</title>\n<style>{_CSS}</style>\n</head>\n<body>\n"
            + "\n".join(body) + "\n</body>\n</html>\n")


# --- writing -----------------------------------------------------------------------------------

def _json_default(value: Any) -> Any:
    if hasattr(value, "item"):
        return value.item()
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return str(value)


def _write_text(path: Path, text: str) -> None:
    from dcfpb.common.files import atomic_output

    with atomic_output(path) as temporary:
        temporary.write_text(text, encoding="utf-8")


def _capacity(result: Any) -> float | None:
    """The bearings' displacement capacity [m]: the analysis's option, else what the governing
    run records, if any."""
    value = (result.options or {}).get("displacement_capacity")
    if value is None and result.governing_run is not None:
        value = result.governing_run.attrs.get("displacement_capacity")
    return None if value is None else float(value)


def draw_figures(result: Any, folder: Path, *, processes: int = 1) -> dict[str, Path | None]:
    """Draw the figures of :data:`FIGURES` that the result has data for into ``folder``; the
    name of each to its path, None for one not drawn."""
    from dcfpb.plotting.base import draw
    from dcfpb.plotting.design import (
        plot_design_displacements,
        plot_design_drifts,
        plot_design_floor_spectra,
        plot_design_hysteresis,
        plot_design_orbit,
        plot_design_spectra,
    )
    from structures.design.limits import limit

    run = result.governing_run
    elf = result.elf
    options = result.options or {}
    heights = options.get("storey_heights")
    if heights is None:
        heights = elf.upper.directions[elf.directions[0]].storey_heights
    d_tm = max(d.D_TM for d in elf.lower.directions.values())
    jobs = [
        ("spectra.png", lambda p: plot_design_spectra(result.spectra, p), 1.0),
        ("displacements.png", lambda p: plot_design_displacements(
            result.peaks, elf, p, capacity=_capacity(result)), 1.0),
        ("drift_ratios.png", lambda p: plot_design_drifts(result.averages, heights,
                                                          limit("drift_rha"), p, elf=elf), 1.0),
    ]
    if run is not None:
        jobs += [
            ("orbit.png", lambda p: plot_design_orbit(run, p, D_M=elf.lower.D_M, D_TM=d_tm),
             1.5),
            ("hysteresis.png", lambda p: plot_design_hysteresis(run, p), 1.5),
        ]
        if "floor_spectrum" in run:
            jobs.append(("floor_spectra.png", lambda p: plot_design_floor_spectra(run, p), 1.0))
    figures = [(folder / name, (lambda f=function, p=folder / name: f(p)), weight)
               for name, function, weight in jobs]
    draw(figures, processes=processes)
    drawn = {name for name, _, _ in jobs}
    return {name: (folder / name if name in drawn else None) for name in FIGURES}


def write_report(result: Any, folder: str | os.PathLike, *, command: str | None = None,
                 processes: int = 1) -> dict[str, Path]:
    """Write the report of ``result`` (a :class:`~structures.design.result.DesignResult`) into
    ``folder`` (made if missing): the documents, data and figures; returns each file written
    by name. Every file is written atomically; existing files of these names are replaced
    (the command line refuses them first without ``--overwrite``)."""
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    figures = draw_figures(result, folder, processes=processes)
    blocks = build_document(result, figures, command=command)
    title = f"Chapter 17 design: {result.name}"
    written: dict[str, Path] = {}
    _write_text(folder / "report.md", render_markdown(blocks))
    _write_text(folder / "report.html", render_html(blocks, title))
    data = result.to_dict()
    data["figures"] = [name for name in FIGURES if figures.get(name) is not None]
    data["files"] = [*REPORT_FILES, *data["figures"]]
    data["display_units"] = {k: v[0] for k, v in _DISPLAY_UNITS.items()}
    _write_text(folder / "design.json", json.dumps(json_safe(data), indent=1, default=_json_default,
                                                   allow_nan=False) + "\n")
    from dcfpb.common.files import atomic_output

    with atomic_output(folder / "peaks.csv") as temporary:
        result.peaks.to_csv(temporary, index=False)
    for name in (*REPORT_FILES, *data["figures"]):
        written[name] = folder / name
    return written
