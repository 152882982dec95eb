"""Imports flow one way: the drawing layer and the writers never import a product, and nothing
below the command line imports it (DESIGN.md, "The flow")."""

from __future__ import annotations

import ast
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
