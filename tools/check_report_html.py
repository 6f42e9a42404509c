"""Check a report's HTML in a real browser: ``python tools/check_report_html.py REPORT_DIR``.

The report of ``dcfpb design`` (``REPORT_DIR/report.html``, the figures beside it) is loaded in
headless Chromium (Debian's ``/usr/bin/chromium``: ``apt-get install -y chromium``; another
binary with ``--chromium PATH`` or ``$CHROMIUM``), and the script verifies that

- the page loads and its title and first heading are there (the DOM as the browser built it,
  ``--dump-dom``);
- every ``<img>`` is complete and decoded by the browser (``naturalWidth > 0``);
- no link is broken: every ``href`` and ``src`` is relative (no scheme, no absolute path: the
  folder can be moved or mailed), a link to a file names one in the folder, a link to an anchor
  (``#checks``) names an element of the page.

The browser's side is a copy of the page in a temporary folder with a ``<base>`` pointing to
REPORT_DIR and a script run on the ``load`` event that writes what it found into the DOM, which
``--dump-dom`` prints (``--virtual-time-budget`` lets it run); REPORT_DIR itself is only read.
With ``--screenshot FILE.png`` a full-page screenshot of the report is saved too.

Exit status 0 when every check passes, 1 when one fails (each printed), 2 when Chromium is
missing or does not start. The pytest test ``tests/unit/test_design_report_browser.py`` runs it
on a report the tests write and skips where ``/usr/bin/chromium`` is absent.
"""

from __future__ import annotations

import argparse
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

DEFAULT_CHROMIUM = "/usr/bin/chromium"
"""Debian's Chromium."""

CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu",
                  "--disable-background-networking", "--no-first-run",
                  "--disable-extensions", "--allow-file-access-from-files",
                  "--virtual-time-budget=10000")
"""The flags every Chromium run gets (the user data folder is a fresh temporary one)."""

_MARK = "dcfpb-browser-check"

_PROBE = """
<script>
window.addEventListener("load", function () {
  var images = Array.prototype.map.call(document.images, function (img) {
    return {src: img.getAttribute("src"), complete: img.complete,
            naturalWidth: img.naturalWidth, naturalHeight: img.naturalHeight};
  });
  var anchors = Array.prototype.map.call(document.querySelectorAll("a[href]"), function (a) {
    var href = a.getAttribute("href");
    var target = href.charAt(0) === "#" ? document.getElementById(href.slice(1)) : null;
    return {href: href, anchor_found: href.charAt(0) === "#" ? target !== null : null};
  });
  var h1 = document.querySelector("h1");
  var out = {title: document.title, h1: h1 ? h1.textContent : null,
             tables: document.querySelectorAll("table").length,
             images: images, anchors: anchors};
  var pre = document.createElement("pre");
  pre.id = "MARK";
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
});
</script>
""".replace("MARK", _MARK)


class _Links(HTMLParser):
    """Every href and src of a page (the static check)."""

    def __init__(self) -> None:
        super().__init__()
        self.links: list[tuple[str, str]] = []
        self.ids: set[str] = set()

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        for name, value in attrs:
            if name in ("href", "src") and value is not None:
                self.links.append((tag, value))
            if name == "id" and value:
                self.ids.add(value)


def static_problems(folder: Path, page: str = "report.html") -> list[str]:
    """The links of ``folder/page`` that are absolute or name a missing file or anchor."""
    text = (folder / page).read_text(encoding="utf-8")
    parser = _Links()
    parser.feed(text)
    problems = []
    for tag, link in parser.links:
        parts = urlsplit(link)
        if parts.scheme or parts.netloc or link.startswith("/"):
            problems.append(f"<{tag}> {link!r} is not a relative link")
            continue
        if parts.path:
            target = folder / unquote(parts.path)
            if not target.is_file():
                problems.append(f"<{tag}> {link!r}: no such file in {folder}")
        if parts.fragment and not parts.path and parts.fragment not in parser.ids:
            problems.append(f"<{tag}> {link!r}: no element with id {parts.fragment!r}")
    return problems


def _probe_page(folder: Path, page: str, work: Path) -> Path:
    """A copy of the page in ``work`` with a ``<base>`` to ``folder`` and the probe script."""
    text = (folder / page).read_text(encoding="utf-8")
    base = f'<base href="{html.escape(folder.resolve().as_uri())}/">'
    text = re.sub(r"(<head[^>]*>)", lambda m: m.group(1) + base, text, count=1)
    text = text.replace("</body>", _PROBE + "</body>", 1)
    probe = work / page
    probe.write_text(text, encoding="utf-8")
    return probe


def run_chromium(chromium: str, arguments: list[str], work: Path,
                 timeout: float = 120.0) -> subprocess.CompletedProcess:
    """Chromium with :data:`CHROMIUM_FLAGS`, a fresh profile in ``work`` and ``arguments``."""
    profile = work / "profile"
    profile.mkdir(exist_ok=True)
    command = [chromium, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", *arguments]
    return subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                          check=False)


def browser_problems(folder: Path, chromium: str, page: str = "report.html",
                     screenshot: Path | None = None) -> tuple[list[str], dict]:
    """Load the page in Chromium: the problems found and what the browser reported."""
    with tempfile.TemporaryDirectory(prefix="dcfpb-chromium-") as name:
        work = Path(name)
        probe = _probe_page(folder, page, work)
        done = run_chromium(chromium, ["--dump-dom", probe.as_uri()], work)
        if screenshot is not None:
            shot = run_chromium(chromium, [f"--screenshot={Path(screenshot).resolve()}",
                                           "--window-size=1280,24000", "--hide-scrollbars",
                                           (folder / page).resolve().as_uri()], work)
            if shot.returncode != 0 or not Path(screenshot).is_file():
                raise RuntimeError(f"chromium --screenshot failed ({shot.returncode}): "
                                   f"{shot.stderr.strip()[-500:]}")
    if done.returncode != 0:
        raise RuntimeError(f"chromium --dump-dom failed ({done.returncode}): "
                           f"{done.stderr.strip()[-500:]}")
    found = re.search(rf'<pre id="{_MARK}">(.*?)</pre>', done.stdout, re.S)
    if found is None:
        return ["the page did not finish loading in Chromium (no load event seen)"], {}
    report = json.loads(html.unescape(found.group(1)))
    problems = []
    if not report.get("h1"):
        problems.append("the page has no <h1> heading")
    if not report.get("title"):
        problems.append("the page has no <title>")
    if not report["images"]:
        problems.append("the page holds no <img>")
    for image in report["images"]:
        if not image["complete"] or image["naturalWidth"] <= 0:
            problems.append(f"<img src={image['src']!r}> not decoded by the browser "
                            f"(complete {image['complete']}, naturalWidth "
                            f"{image['naturalWidth']})")
    for anchor in report["anchors"]:
        if anchor["anchor_found"] is False:
            problems.append(f"<a href={anchor['href']!r}>: no such element in the page")
    return problems, report


def find_chromium(given: str | None = None) -> str | None:
    """The Chromium binary: ``given``, ``$CHROMIUM``, :data:`DEFAULT_CHROMIUM` or ``chromium``
    on the PATH; None when there is none."""
    for candidate in (given, os.environ.get("CHROMIUM"), DEFAULT_CHROMIUM):
        if candidate and Path(candidate).is_file() and os.access(candidate, os.X_OK):
            return candidate
    return shutil.which("chromium") or shutil.which("chromium-browser")


def check(folder: str | os.PathLike, *, chromium: str | None = None, page: str = "report.html",
          screenshot: str | os.PathLike | None = None) -> tuple[list[str], dict]:
    """Every problem of ``folder/page`` (static and in the browser) and the browser's report.

    Raises
    ------
    FileNotFoundError
        No such page, or no Chromium.
    RuntimeError
        Chromium did not run.
    """
    folder = Path(folder)
    if not (folder / page).is_file():
        raise FileNotFoundError(f"{folder / page}: no such page")
    binary = find_chromium(chromium)
    if binary is None:
        raise FileNotFoundError("no Chromium found (apt-get install -y chromium, or give "
                                "--chromium PATH)")
    problems = static_problems(folder, page)
    found, report = browser_problems(folder, binary, page,
                                     None if screenshot is None else Path(screenshot))
    return problems + found, report


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", metavar="REPORT_DIR", help="folder holding report.html")
    parser.add_argument("--page", default="report.html", help="the page (default report.html)")
    parser.add_argument("--chromium", help=f"Chromium binary (default {DEFAULT_CHROMIUM})")
    parser.add_argument("--screenshot", metavar="FILE.png",
                        help="save a full-page screenshot of the report")
    args = parser.parse_args(argv)
    try:
        problems, report = check(args.folder, chromium=args.chromium, page=args.page,
                                 screenshot=args.screenshot)
    except (FileNotFoundError, RuntimeError, subprocess.TimeoutExpired) as error:
        print(f"check_report_html: {error}", file=sys.stderr)
        return 2
    for problem in problems:
        print(f"FAIL: {problem}")
    images = report.get("images", [])
    print(f"{'FAIL' if problems else 'OK'}: {args.folder}/{args.page} loaded in Chromium, "
          f"{sum(i['naturalWidth'] > 0 for i in images)} of {len(images)} images decoded, "
          f"{len(report.get('anchors', []))} links, {report.get('tables', 0)} tables"
          + (f"; screenshot {args.screenshot}" if args.screenshot else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
