"""Imports flow one way: the drawing layer and the writers never import a product, nothing below
the command line imports it, no module imports itself through others (no cycle, even through an
import inside a function), and modules stay small enough to read (DESIGN.md, "The flow")."""

from __future__ import annotations

import ast
import shutil
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "weavecut"
PRODUCTS = {"papermodel", "puzzle", "figures"}
# package -> packages it must never import
FORBIDDEN = {
    "mesh_core": {"subdivision", "weave", "analysis", "layout", *PRODUCTS, "export", "cli"},
    "subdivision": {"weave", "layout", *PRODUCTS, "export", "cli"},
    "weave": {"layout", *PRODUCTS, "export", "cli"},
    "layout": PRODUCTS | {"cli"},
    "export": PRODUCTS | {"cli"},
    "papermodel": {"puzzle", "figures", "cli"},
    "puzzle": {"papermodel", "figures", "cli"},
    "figures": {"cli"},
    "analysis": {"layout", *PRODUCTS, "export", "cli"},
    "readers": {"subdivision", "weave", "analysis", "layout", *PRODUCTS, "export", "cli"},
}


def package_of(path: Path) -> str:
    rel = path.relative_to(SRC)
    return rel.parts[0] if len(rel.parts) > 1 else "mesh_core"


def imported_packages(path: Path, text: str | None = None) -> set[str]:
    """weavecut subpackages named by the imports of one module (relative or absolute)."""
    tree = ast.parse(path.read_text(encoding="utf-8") if text is None else text)
    here = path.relative_to(SRC).parent.parts
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = list(here[: len(here) - (node.level - 1)]) if node.level > 1 else list(here)
                target = base + (node.module.split(".") if node.module else [])
                names = [target + [a.name] for a in node.names] if not node.module else [target]
            elif node.module and node.module.startswith("weavecut."):
                names = [node.module.split(".")[1:]]
            else:
                continue
            found.update(n[0] for n in names if n)
        elif isinstance(node, ast.Import):
            found.update(a.name.split(".")[1] for a in node.names
                         if a.name.startswith("weavecut."))
    return found


MODULES = sorted(p for p in SRC.rglob("*.py") if p.name != "__main__.py")
LONGEST = 400  # lines; a longer module says why in its first line: "# over 400 lines: ..."


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_imports_flow_one_way(path):
    bad = imported_packages(path) & FORBIDDEN.get(package_of(path), set())
    assert not bad, f"{path.relative_to(SRC)} imports {sorted(bad)}"


def test_the_checker_sees_relative_imports():
    """Plant the bug: product imports written in each style must be seen."""
    assert "puzzle" in imported_packages(SRC / "layout" / "x.py", "from ..puzzle import pieces")
    assert "papermodel" in imported_packages(SRC / "layout" / "x.py",
                                             "from ..papermodel.strips import x")
    assert "figures" in imported_packages(SRC / "cli" / "x.py", "from .. import figures")
    assert "puzzle" in imported_packages(SRC / "export" / "x.py", "import weavecut.puzzle.files")


FRONT_ENDS = {"cli", "web"}  # the top floor: the command line and the web app over it


def test_nothing_below_the_front_ends_imports_them():
    """cli/ and web/ are the top floor: no other module (a package's ``__main__`` too) imports
    either, but ``python -m weavecut``, which runs the CLI; web/ may import cli/ (its forms
    are the commands' options) and cli/ may import web/ (``serve``)."""
    bad = [f"{p.relative_to(SRC)} imports {sorted(FRONT_ENDS & imported_packages(p))}"
           for p in SRC.rglob("*.py") if p != SRC / "__main__.py"
           and package_of(p) not in FRONT_ENDS and FRONT_ENDS & imported_packages(p)]
    assert not bad, f"below the front ends: {bad}"


def test_the_web_app_does_not_import_the_commands_that_start_it():
    """web/ imports the click group and its command modules, never ``serve_command`` (or a
    ``worker_command``), which import web/: no module-level cycle between the floors."""
    starters = {"weavecut.cli.serve_command", "weavecut.cli.worker_command"}
    graph = import_graph(SRC)
    bad = {m: sorted(graph[m] & starters) for m in graph
           if m.startswith("weavecut.web") and graph[m] & starters}
    assert not bad


# --- cycles -------------------------------------------------------------------------------

def module_name(path: Path, root: Path) -> str:
    """``weavecut.papermodel.book`` for ``root/papermodel/book.py`` (a package: its folder)."""
    parts = path.relative_to(root).with_suffix("").parts
    return ".".join((root.name, *(parts[:-1] if parts[-1] == "__init__" else parts)))


def import_graph(root: Path) -> dict[str, set[str]]:
    """Module -> the modules of the package at ``root`` it imports: every ``import`` and
    ``from ... import`` anywhere in it (inside functions and ``TYPE_CHECKING`` too), relative
    or absolute; ``from pkg import sub`` imports the module ``pkg.sub``, not ``pkg``'s
    ``__init__`` unless a name comes from it."""
    files = {module_name(p, root): p for p in root.rglob("*.py")}
    graph = {}
    for name, path in files.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found.update(a.name for a in node.names if a.name in files)
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package.split(".")[: len(package.split(".")) - node.level + 1]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                subs = {f"{target}.{a.name}" for a in node.names} & files.keys()
                found |= subs
                if target in files and len(subs) < len(node.names):
                    found.add(target)
        graph[name] = found - {name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Every strongly connected group of more than one module (Tarjan), each as a sorted list:
    empty when imports flow one way."""
    index, low, stack, on, groups = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return groups


def test_no_import_cycles():
    assert cycles(import_graph(SRC)) == []


@pytest.mark.slow
def test_a_planted_cycle_is_found(tmp_path):
    """Plant the bug: a copy of the package where a low module imports a product inside a
    function (as units once imported presets) has a cycle; each import style is followed."""
    root = tmp_path / "weavecut"
    shutil.copytree(SRC, root)
    assert cycles(import_graph(root)) == []
    units = root / "units.py"
    units.write_text(units.read_text() + "\n\ndef late():\n    from . import presets\n")
    assert cycles(import_graph(root)) == [["weavecut.presets", "weavecut.schema",
                                           "weavecut.units"]]
    units.write_text(units.read_text().replace("from . import presets",
                                               "from weavecut.presets import load"))
    assert cycles(import_graph(root)) == [["weavecut.presets", "weavecut.schema",
                                           "weavecut.units"]]
    mesh = root / "mesh.py"  # mesh -> papermodel.book -> ... -> mesh
    mesh.write_text(mesh.read_text() + "\nimport weavecut.papermodel.book\n")
    found = cycles(import_graph(root))
    assert any({"weavecut.mesh", "weavecut.papermodel.book"} <= set(g) for g in found)


def test_sibling_imports_name_the_module_not_the_package(tmp_path):
    pkg = tmp_path / "p"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("from .a import f\n")
    (pkg / "a.py").write_text("from . import b\n")
    (pkg / "b.py").write_text("X = 1\n")
    (pkg / "sub" / "__init__.py").write_text("")
    (pkg / "sub" / "c.py").write_text("from .. import X_FROM_INIT\nfrom ..b import X\n")
    assert import_graph(pkg) == {"p": {"p.a"}, "p.a": {"p.b"}, "p.b": set(), "p.sub": set(),
                                 "p.sub.c": {"p", "p.b"}}
    assert cycles(import_graph(pkg)) == []
    (pkg / "b.py").write_text("from .sub.c import Y\n")  # p -> a -> b -> sub.c -> p
    assert cycles(import_graph(pkg)) == [["p", "p.a", "p.b", "p.sub.c"]]


# --- size ---------------------------------------------------------------------------------

@pytest.mark.parametrize("path", sorted(SRC.rglob("*.py")), ids=lambda p: str(p.relative_to(SRC)))
def test_modules_stay_readable(path):
    lines = path.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= LONGEST or lines[0].startswith(f"# over {LONGEST} lines: "), (
        f"{path.relative_to(SRC)} has {len(lines)} lines: split it along a seam its docstring "
        f"names, or say why it must stay whole in its first line (# over {LONGEST} lines: ...)")
