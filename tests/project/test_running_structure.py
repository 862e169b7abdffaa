"""The running linkage's structure: studies compose the physics below them and read no other
module's private names; the speed terms are assembled in one function; the rev/min factor is
defined once. Read with ``ast`` and regular expressions from the package's own files."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import flexlink

PACKAGE = Path(flexlink.__file__).parent
ASSEMBLY = PACKAGE / "fe" / "speed_terms.py"
# the element-level builders of the speed terms: only the one assembly function calls them
BUILDERS = {"rotating_entries", "geometric_entries", "inertia_loads", "static_displacement"}
RPM_FACTOR = re.compile(r"2(\.0)?\s*\*\s*(math|np|numpy)\.pi\s*/\s*60|"
                        r"60(\.0)?\s*/\s*\(?\s*2(\.0)?\s*\*\s*(math|np|numpy)\.pi|"
                        r"(math|np|numpy)\.pi\s*/\s*30")


def _modules(folder: Path = PACKAGE):
    for path in sorted(folder.rglob("*.py")):
        yield path, ast.parse(path.read_text(), filename=str(path))


def private_imports(tree: ast.AST) -> list[str]:
    """``from flexlink... import _name`` in a module, as 'module._name'."""
    return [f"{node.module}.{alias.name}" for node in ast.walk(tree)
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("flexlink")
            for alias in node.names if alias.name.startswith("_")
            and not alias.name.startswith("__")]


def foreign_private_reads(tree: ast.AST) -> list[str]:
    """``x._name`` where x is not ``self`` or ``cls``: another object's private state."""
    return [f"{ast.unparse(node.value)}.{node.attr}" for node in ast.walk(tree)
            if isinstance(node, ast.Attribute) and node.attr.startswith("_")
            and not node.attr.startswith("__")
            and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))]


def builder_calls(tree: ast.AST) -> set[str]:
    """The speed-term builders ``tree`` calls, by name or as attributes."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            name = getattr(node.func, "id", None) or getattr(node.func, "attr", None)
            if name in BUILDERS:
                out.add(name)
    return out


def test_no_study_imports_or_reads_another_modules_private_names():
    found = {str(path.relative_to(PACKAGE)): private_imports(tree) + foreign_private_reads(tree)
             for path, tree in _modules(PACKAGE / "studies")}
    assert {k: v for k, v in found.items() if v} == {}


def test_the_speed_terms_are_assembled_in_one_function():
    callers = {str(path.relative_to(PACKAGE)): sorted(builder_calls(tree))
               for path, tree in _modules() if path != ASSEMBLY}
    # each builder is called by its own module's helpers and by the assembly, nowhere else
    own = {"fe/rotating.py", "fe/preload.py", "fe/geometric.py"}
    assert {k: v for k, v in callers.items() if v and k not in own} == {}
    tree = ast.parse(ASSEMBLY.read_text())
    assembling = [node.name for node in tree.body if isinstance(node, ast.FunctionDef)
                  and builder_calls(node)]
    assert assembling == ["speed_terms"]


def test_no_study_or_renderer_builds_speed_terms_or_serves_them():
    # the running floor's studies take the terms from fe/ and analysis/, and no study is
    # imported by another running study
    for path, tree in _modules(PACKAGE / "studies" / "running"):
        imported = {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
        assert not {m for m in imported if m and m.startswith("flexlink.studies.running")}, path


def test_the_rev_per_min_factor_is_defined_once():
    defined = []
    for path, tree in _modules():
        text = path.read_text()
        if RPM_FACTOR.search(text):
            defined.append(str(path.relative_to(PACKAGE)))
        for node in tree.body:  # a module-level constant named for the factor
            targets = node.targets if isinstance(node, ast.Assign) else (
                [node.target] if isinstance(node, ast.AnnAssign) else [])
            if any(isinstance(t, ast.Name) and t.id == "RPM" for t in targets):
                defined.append(f"{path.relative_to(PACKAGE)}: RPM")
    assert defined == ["units.py", "units.py: RPM"]
