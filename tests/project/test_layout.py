"""The package's shape: lower stages never import higher ones, no two modules import each other
(directly or round a loop), the kinematics stage stays light, studies and kinematics neither
write files nor draw, and a public name means one thing.

Imports are read with ``ast`` from every module, function-level imports included, so a lazy
import inside a command or a drawing function counts like a top-level one."""

from __future__ import annotations

import ast
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

import flexlink

PACKAGE_DIR = Path(flexlink.__file__).parent

# Stage of each first-level name under flexlink; a module may import its own stage or lower.
LAYERS = {
    "": 0, "errors": 0, "units": 0, "fileio": 0, "parallel": 0, "logbook": 0, "stopping": 0,
    "meshes": 0, "choices": 0,
    "materials": 1, "kinematics": 1,
    "fe": 2, "scene": 3, "analysis": 4, "studies": 5, "output": 6, "commands": 7, "cli": 8,
}


# Public names defined in more than one module: only the command convention is meant to be
# shared (every command module defines ``command``).
SHARED_NAMES = {"command"}


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE_DIR.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def all_modules() -> dict[str, Path]:
    return {module_name(p): p for p in sorted(PACKAGE_DIR.rglob("*.py"))}


def imported_modules(name: str, path: Path, known: set[str]) -> set[str]:
    """flexlink modules that module ``name`` imports anywhere in its body. ``from a import b``
    counts as importing ``a.b`` when that is a module, else ``a``."""
    is_package = path.name == "__init__.py"
    found = set()
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = name.split(".")
                base = base[:len(base) - node.level + (1 if is_package else 0)]
                source = ".".join(base + ([node.module] if node.module else []))
            else:
                source = node.module or ""
            targets = [f"{source}.{alias.name}" if f"{source}.{alias.name}" in known else source
                       for alias in node.names]
        else:
            continue
        for target in targets:
            while target and target not in known:  # `import flexlink.fe.model.x` -> the module
                target = target.rpartition(".")[0]
            if target.startswith("flexlink"):
                found.add(target)
    found.discard(name)
    return found


def import_graph() -> dict[str, set[str]]:
    modules = all_modules()
    return {name: imported_modules(name, path, set(modules)) for name, path in modules.items()}


def layer(module: str) -> int:
    parts = module.split(".")
    return LAYERS[parts[1] if len(parts) > 1 else ""]


def upward_imports(graph: dict[str, set[str]]) -> list[str]:
    return sorted(f"{a} (stage {layer(a)}) imports {b} (stage {layer(b)})"
                  for a, targets in graph.items() for b in targets if layer(b) > layer(a))


def cycles(graph: dict[str, set[str]]) -> list[frozenset[str]]:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(frozenset(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_every_module_has_a_stage():
    assert {m.split(".")[1] if "." in m else "" for m in all_modules()} <= set(LAYERS)


def test_no_upward_import():
    assert upward_imports(import_graph()) == []


def test_no_import_cycle():
    assert [sorted(c) for c in cycles(import_graph())] == []


def test_checker_sees_upward_and_cyclic_imports(tmp_path):
    """The walk itself: a relative import inside a function and a two-module loop are found."""
    source = tmp_path / "model.py"
    source.write_text("def build():\n    from ..scene import load\n    return load\n")
    known = set(all_modules())
    graph = {"flexlink.fe.model": imported_modules("flexlink.fe.model", source, known)}
    assert graph["flexlink.fe.model"] == {"flexlink.scene.load"}
    assert upward_imports(graph) == [
        "flexlink.fe.model (stage 2) imports flexlink.scene.load (stage 3)"]
    graph["flexlink.scene.load"] = {"flexlink.fe.model"}
    assert cycles(graph) == [frozenset(graph)]


def test_one_module_per_public_name():
    defined = defaultdict(list)
    for name, path in all_modules().items():
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, (ast.FunctionDef, ast.ClassDef)) and not node.name.startswith("_"):
                defined[node.name].append(name)
    shared = {k: v for k, v in defined.items() if len(v) > 1}
    assert set(shared) - SHARED_NAMES == set(), shared


# Stages that compute and return results: they neither write files nor draw.
QUIET_STAGES = ("studies", "kinematics")
DRAWING_LIBRARIES = {"matplotlib", "plotly", "pyvista"}
WRITING_CALLS = {"write_atomic", "write_atomic_with", "staged_folder", "write_text",
                 "write_bytes", "savefig", "to_csv", "savetxt", "save", "savez",
                 "savez_compressed", "dump"}
OPEN_MODE = set("rwaxbt+")


def _called_name(node: ast.Call) -> str | None:
    if isinstance(node.func, ast.Name):
        return node.func.id
    if isinstance(node.func, ast.Attribute):
        return node.func.attr
    return None


def _opens_for_writing(node: ast.Call) -> bool:
    """``open(path, "w")``, ``Path.open("a")``, ``open(path, mode="wb")``...: a string argument
    made of mode letters that asks to write, append, create or update."""
    texts = [a.value for a in [*node.args, *(k.value for k in node.keywords if k.arg == "mode")]
             if isinstance(a, ast.Constant) and isinstance(a.value, str)]
    return any(text and set(text) <= OPEN_MODE and set(text) & set("wax+") for text in texts)


def writes_or_draws(path: Path) -> list[str]:
    """What module ``path`` does that only ``output/`` may: file-writing calls and imports of
    drawing libraries, anywhere in its body (inside functions too), as "line: what"."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            roots = {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom):
            roots = {(node.module or "").split(".")[0]} if not node.level else set()
        elif isinstance(node, ast.Call):
            name = _called_name(node)
            if name in WRITING_CALLS or (name == "open" and _opens_for_writing(node)):
                found.append(f"{node.lineno}: calls {name}")
            continue
        else:
            continue
        found += [f"{node.lineno}: imports {root}" for root in sorted(roots & DRAWING_LIBRARIES)]
    return sorted(found, key=lambda line: int(line.split(":")[0]))


def test_studies_and_kinematics_neither_write_nor_draw():
    """Only ``output/`` renders: a study or the kinematics returns its result, and the command
    hands it to ``output/``, which writes through ``fileio``."""
    offenders = {name: found for name, path in all_modules().items()
                 if name.split(".")[1:2] and name.split(".")[1] in QUIET_STAGES
                 and (found := writes_or_draws(path))}
    assert offenders == {}


def test_checker_sees_writes_and_drawing_imports(tmp_path):
    """The walk itself: writes and drawing imports inside functions are found, reading is not."""
    source = tmp_path / "study.py"
    source.write_text(
        "import json\n"
        "def plot(result, path):\n"
        "    import matplotlib.pyplot as plt\n"
        "    from plotly import graph_objects\n"
        "    plt.figure().savefig(path)\n"
        "def save(path, text, frame):\n"
        "    from flexlink.fileio import write_atomic\n"
        "    write_atomic(path, text)\n"
        "    path.write_text(text)\n"
        "    frame.to_csv(path)\n"
        "    with open(path, mode='a') as fh:\n"
        "        json.dump({}, fh)\n"
        "    with path.open('wb'):\n"
        "        pass\n"
        "def read(path):\n"
        "    with open(path) as fh, open('/proc/self/status', 'r') as gh:\n"
        "        return fh.read() + gh.read()\n")
    assert writes_or_draws(source) == [
        "3: imports matplotlib", "4: imports plotly", "5: calls savefig", "8: calls write_atomic",
        "9: calls write_text", "10: calls to_csv", "11: calls open", "12: calls dump",
        "13: calls open"]


def test_kinematics_loads_no_fe_or_sparse_solver():
    code = ("import sys, flexlink.kinematics, flexlink.kinematics.motion, "
            "flexlink.kinematics.synthesis; "
            "print(sorted(m for m in ('skfem', 'scipy.sparse.linalg') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=PACKAGE_DIR.parent)
    assert out.stdout.strip() == "[]"


def test_pyproject_lists_every_package():
    """pyproject.toml lists the packages (one is mapped from materials/): a new sub-package
    missing from the list would be left out of the wheel."""
    import tomllib

    config = tomllib.loads((PACKAGE_DIR.parent / "pyproject.toml").read_text())["tool"]["setuptools"]
    packages = {module_name(p) for p in PACKAGE_DIR.rglob("__init__.py")}
    assert set(config["packages"]) == packages | {"flexlink.materials.data"}
    assert config["package-dir"] == {"flexlink.materials.data": "materials"}


# Renderers with no study module of their own name: the calibration study's Markdown report
# beside its JSON document, and the line a synthesised scene prints above any result.
RENDERERS_WITHOUT_A_NAMESAKE = {"calibration.calibration_report", "pose.synthesis_text"}


def test_output_mirrors_studies_question_for_question():
    """``output/<question>/<module>.py`` renders ``studies/<question>/<module>.py``: every
    renderer grouped under a question has a study of the same name there, so the one that
    renders a study is found by its path."""
    studies = PACKAGE_DIR / "studies"
    output = PACKAGE_DIR / "output"
    questions = sorted(p.name for p in output.iterdir() if (p / "__init__.py").exists())
    assert questions, "output/ has no question sub-packages"
    orphans = [f"{q}.{p.stem}" for q in questions for p in sorted((output / q).glob("*.py"))
               if p.stem != "__init__" and not (studies / q / p.name).exists()
               and f"{q}.{p.stem}" not in RENDERERS_WITHOUT_A_NAMESAKE]
    assert orphans == [], f"renderers with no study of their name: {orphans}"
