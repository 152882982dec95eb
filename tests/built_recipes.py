"""Recipes built once per test session (``once.py``: the xdist workers share each build), for
the tests that read what a recipe's build writes: its files (``test_no_machine_paths``) and
the cut outlines of the Drawings its commands write (``papermodel/test_slim_pieces``).

Each recipe is built with ``weave-cut -q build RECIPE -o OUT`` given absolute paths (``OUT``
lies in the session's shared folder), as a maker's shell would run it (``sys.argv`` is that
command, which the files record). The cut outlines come back exactly (WKB holds the doubles)."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest
import shapely
from click.testing import CliRunner

from weavecut import export
from weavecut.cli import cli
from weavecut.layout.drawing import Polygons

from .once import once, session_root


def cut_outlines(drawing) -> list[list[shapely.Geometry]]:
    """Per sheet, the outlines on its cut layers, in the Drawing's order."""
    return [[g for layer in sheet.layers if layer.role == "cut" for shape in layer.shapes
             if isinstance(shape, Polygons) for g in shape.to_shapely().tolist()]
            for sheet in drawing.sheets]


def _build(recipe: Path, out: Path) -> dict:
    out.parent.mkdir(parents=True, exist_ok=True)
    args = ["-q", "build", str(recipe), "-o", str(out)]
    written = []
    original = export.write

    def keep(drawing, path, *rest, **kwargs):
        written.append([Path(path).resolve().relative_to(out.resolve()).as_posix(),
                        [shapely.to_wkb(cut, hex=True).tolist() for cut in cut_outlines(drawing)]])
        return original(drawing, path, *rest, **kwargs)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(export, "write", keep)
        patch.setattr(sys, "argv", ["weave-cut", *args])  # the command files record
        res = CliRunner().invoke(cli, args)
    assert res.exit_code == 0, res.output
    return {"out": str(out), "written": written}


def built(factory: pytest.TempPathFactory, recipe: Path) -> tuple[Path, list]:
    """The folder ``recipe`` was built into this session, and what its commands wrote:
    [(file path within the folder, per sheet the cut outlines)] in the order written."""
    root = session_root(factory)
    made = once(root, f"build {recipe}", lambda: _build(recipe, root / "recipes" / recipe.stem))
    return Path(made["out"]), [(name, [list(shapely.from_wkb(sheet)) for sheet in sheets])
                               for name, sheets in made["written"]]
