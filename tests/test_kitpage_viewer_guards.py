"""The kit page's 3-D viewer takes only what it can show (each check disabled once by
``tests/hand_audit/guards.py``, #34): a ``.glb`` larger than the page may carry, or a file named
``.glb`` that is not glTF binary, is linked, not embedded; and a page without a model carries
none of the viewer's scripts (three.js alone is over half a megabyte)."""

from __future__ import annotations

import base64
import re
from pathlib import Path

from weavecut import kitpage
from weavecut.fileio import recording, write_atomic
from weavecut.kitpage import viewer

GLB = b"glTF" + bytes(range(2, 250))  # the magic, then bytes the page need not understand


def page_of(folder: Path, data: bytes | None) -> str:
    """The kit page of a run that wrote a summary and, unless None, ``model.glb``."""
    with recording() as record:
        write_atomic(folder / "summary.json", b'{"tiles": 5}\n')
        if data is not None:
            write_atomic(folder / "model.glb", data)
    kitpage.write(folder / "index.html", "models", [kitpage.Run.of(record, "weave-cut x")])
    return (folder / "index.html").read_text(encoding="utf-8")


def embedded(text: str) -> list[bytes]:
    return [base64.b64decode(m) for m in re.findall(
        r'<script type="model/gltf-binary">([^<]*)</script>', text)]


def test_a_model_is_embedded_once_with_the_viewer_scripts(tmp_path):
    text = page_of(tmp_path, GLB)
    assert embedded(text) == [GLB]
    assert text.split("<script>", 1)[0].count(viewer.MARK) == 1
    assert text.count("WeaveCutThree=") == 1


def test_a_glb_that_is_not_gltf_binary_is_only_linked(tmp_path):
    text = page_of(tmp_path, b'{"asset": {"version": "2.0"}}' + GLB)  # glTF JSON, not binary
    assert embedded(text) == [] and viewer.MARK not in text
    assert 'href="model.glb"' in text
    assert "<script>" not in text  # no viewer: none of its scripts either


def test_a_page_without_a_model_carries_no_viewer_scripts(tmp_path):
    text = page_of(tmp_path, None)
    assert "<script>" not in text and "WeaveCutThree" not in text
    assert viewer.scripts(text) == ""


def test_a_model_larger_than_the_page_may_carry_is_only_linked(tmp_path, monkeypatch):
    monkeypatch.setattr(viewer, "MAX_EMBEDDED", len(GLB))
    assert embedded(page_of(tmp_path, GLB)) == [GLB]  # at the limit: embedded
    text = page_of(tmp_path, GLB + b"\0")
    assert embedded(text) == [] and viewer.MARK not in text and 'href="model.glb"' in text
    monkeypatch.undo()
    big = tmp_path / "big.glb"  # the real limit, on a sparse file: never read whole
    with big.open("wb") as f:
        f.write(b"glTF")
        f.truncate(viewer.MAX_EMBEDDED + 1)
    assert viewer.figure(big, "big.glb") == ""
