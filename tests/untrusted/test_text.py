"""Names with control characters and bytes that are not UTF-8 land in titles, <desc>, PDF
metadata and PNG chunks: every output stays well-formed, and JSON never holds NaN."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import ezdxf
import pytest
from PIL import Image

from weavecut.text import clean

from .helpers import strict_json, well_formed_xml

COMMAND = os.fsencode(Path(sys.executable).with_name("weave-cut"))
NAME = b"m\x01\x1b[31m\xff\xfe<&>.obj"  # a control character, an escape, invalid UTF-8, markup


@pytest.fixture
def mesh(tmp_path) -> bytes:
    path = os.fsencode(tmp_path) + b"/" + NAME
    with open(path, "wb") as f:
        f.write(b"v 0 0\nv 1 0\nv 1 1\nv 0 1\nf 1 2 3 4\n")
    return path


def weave_cut(*args: bytes, cwd=None) -> subprocess.CompletedProcess:
    proc = subprocess.run([COMMAND, *args], capture_output=True, timeout=120, cwd=cwd)
    assert proc.returncode == 0, proc.stderr
    return proc


def test_clean_replaces_what_xml_and_utf8_cannot_hold():
    text = "a\x00b\x1fc\x7fd\x85e\udcfff\ufffeg\tz"
    assert clean(text) == "a\ufffdb\ufffdc\ufffdd\ufffde\ufffdf\ufffdg\ufffdz"
    assert clean("plain <&> text é") == "plain <&> text é"


@pytest.mark.parametrize("suffix", ["svg", "pdf", "png", "dxf"])
def test_drawings_stay_well_formed(tmp_path, mesh, suffix):
    out = tmp_path / f"out.{suffix}"
    weave_cut(b"subdivide", mesh, b"--levels", b"1", b"-o", os.fsencode(out))
    if suffix == "svg":
        root = well_formed_xml(out)
        desc = "".join(root.itertext())
        assert "\ufffd" in desc and "<&>" in desc
    elif suffix == "png":
        info = Image.open(out).text
        assert all(clean(v) == v for v in info.values())
    elif suffix == "dxf":
        doc = ezdxf.readfile(out)
        assert not doc.audit().has_errors
    elif shutil.which("pdfinfo"):
        proc = subprocess.run(["pdfinfo", out], capture_output=True, text=True)
        assert proc.returncode == 0 and "Syntax Error" not in proc.stderr, proc.stderr


@pytest.mark.slow
def test_weave_svg_and_json_stay_well_formed(tmp_path, mesh):
    weave_cut(b"weave", mesh, b"--levels", b"1", b"-o", os.fsencode(tmp_path / "w.svg"))
    well_formed_xml(tmp_path / "w.svg")
    proc = weave_cut(b"stats", mesh, b"--json")
    assert strict_json(proc.stdout)["levels"]
    weave_cut(b"subdivide", mesh, b"-o", os.fsencode(tmp_path / "m.json"))
    assert strict_json((tmp_path / "m.json").read_bytes())["faces"]


def test_recipe_names_with_control_characters(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "subdivide"\ninput = "pentagon"\n'
                      'output = "a\\u0007b.svg"\n')
    weave_cut(b"-q", b"build", os.fsencode(recipe), b"-o", os.fsencode(tmp_path / "out"))
    (svg,) = (tmp_path / "out").glob("a*b.svg")
    well_formed_xml(svg)
