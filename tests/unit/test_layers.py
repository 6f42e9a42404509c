"""The layer contract of ARCHITECTURE.md, checked on the source: imports point down only, and no
module imports itself back through others.

Every ``import`` and ``from ... import`` statement of the four packages is read from the source
(including those inside functions, which run later but are imports all the same) and each module
is given the layer of the longest package prefix in :data:`LAYERS`. An import of a higher layer,
or of a sibling declared independent, fails the contract; so does any cycle in the graph of
module imports. The checker is a plain function of a source folder, so one test shows it catching
a deliberate upward import in a copy of the tree (the tree itself is never touched).
"""

from __future__ import annotations

import ast
import shutil
from collections.abc import Iterable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("dcfpb", "groundmotions", "isolator", "structures")

LAYERS: tuple[tuple[str, ...], ...] = (
    ("dcfpb.cli",),
    ("dcfpb.report",),
    ("dcfpb.plotting",),
    ("structures.design.response",),  # the response history of 17.6 runs suites
    ("structures.suites", "structures.diagnosis", "structures.design"),
    ("structures.opensees",),
    ("structures",),
    ("isolator",),
    ("groundmotions",),
    ("dcfpb.common.validation",),
    ("dcfpb", "dcfpb.common.errors", "dcfpb.common.units", "dcfpb.common.lazy",
     "dcfpb.common.files"),
)
"""From the top down; names on one line are independent siblings (neither imports the other)."""


def _module_name(path: Path, root: Path) -> str:
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _type_only(tree: ast.AST) -> set[int]:
    """ids of the import statements under ``if TYPE_CHECKING:`` (annotations only)."""
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            found.update(id(inner) for branch in node.body for inner in ast.walk(branch))
    return found


def _imported(tree: ast.AST, module: str, is_package: bool, *,
              runtime_only: bool = False) -> Iterable[str]:
    """Absolute names of the modules (or names in modules) one source file imports."""
    package = module if is_package else module.rpartition(".")[0]
    skip = _type_only(tree) if runtime_only else set()
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            yield base
            yield from (f"{base}.{alias.name}" for alias in node.names)


def import_graph(root: Path, *, runtime_only: bool = False) -> dict[str, set[str]]:
    """Module name -> the project's modules it imports, for the packages under ``root``.

    ``runtime_only`` leaves out the imports under ``if TYPE_CHECKING:``, which never run: they
    count for the layers but cannot close a cycle.
    """
    files = {
        _module_name(path, root): path
        for package in PACKAGES
        for path in (root / package).rglob("*.py")
    }
    graph: dict[str, set[str]] = {}
    for name, path in files.items():
        tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
        targets = set()
        for target in _imported(tree, name, path.name == "__init__.py",
                                runtime_only=runtime_only):
            while target and target not in files:  # `from a.b import name` -> module a.b
                target = target.rpartition(".")[0]
            if target and target != name:
                targets.add(target)
        graph[name] = targets
    return graph


def layer_of(module: str) -> tuple[int, str]:
    """(level, owner) of a module: 0 is the top layer; owner is the matching LAYERS name."""
    best: tuple[int, str] | None = None
    for level, names in enumerate(LAYERS):
        for owner in names:
            matches = module == owner or module.startswith(owner + ".")
            if matches and (best is None or len(owner) > len(best[1])):
                best = (level, owner)
    if best is None:
        raise AssertionError(f"module {module} is in no layer of LAYERS")
    return best


def upward_imports(graph: dict[str, set[str]]) -> list[str]:
    """Every import of a higher layer or of an independent sibling, as readable lines."""
    found = []
    for module, targets in sorted(graph.items()):
        level, owner = layer_of(module)
        for target in sorted(targets):
            target_level, target_owner = layer_of(target)
            if target_level < level or (target_level == level and target_owner != owner):
                found.append(f"{module} (layer {owner}) imports {target} (layer {target_owner})")
    return found


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for nxt in graph.get(node, ()):
            if nxt not in index:
                visit(nxt)
                low[node] = min(low[node], low[nxt])
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
        if low[node] == index[node]:
            component = []
            while True:
                top = stack.pop()
                on_stack.discard(top)
                component.append(top)
                if top == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def test_every_module_has_a_layer():
    for module in import_graph(ROOT):
        layer_of(module)


def test_imports_point_down_only():
    assert upward_imports(import_graph(ROOT)) == []


def test_no_module_imports_itself_back():
    assert cycles(import_graph(ROOT, runtime_only=True)) == []


def test_the_contract_catches_an_upward_import(tmp_path):
    """A deliberate bad import, in a copy of the tree, fails both checks."""
    for package in PACKAGES:
        shutil.copytree(ROOT / package, tmp_path / package,
                        ignore=shutil.ignore_patterns("__pycache__", "data"))
    assert upward_imports(import_graph(tmp_path)) == []
    spectra = tmp_path / "groundmotions" / "spectra.py"
    spectra.write_text(spectra.read_text() + "\n\ndef _bad():\n    from dcfpb.cli import main\n")
    found = upward_imports(import_graph(tmp_path))
    assert found == ["groundmotions.spectra (layer groundmotions) imports dcfpb.cli "
                     "(layer dcfpb.cli)"]
    records = tmp_path / "groundmotions" / "records.py"
    records.write_text(records.read_text() + "\nimport groundmotions.synthetic\n")  # a loop
    assert any("groundmotions.records" in component and "groundmotions.synthetic" in component
               for component in cycles(import_graph(tmp_path, runtime_only=True)))


def test_independent_siblings_may_not_import_each_other(tmp_path):
    graph = {"structures.suites.runs": {"structures.diagnosis.truths"},
             "structures.diagnosis.truths": set()}
    assert upward_imports(graph) == [
        "structures.suites.runs (layer structures.suites) imports structures.diagnosis.truths "
        "(layer structures.diagnosis)"]
