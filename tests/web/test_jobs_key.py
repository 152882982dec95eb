"""The cache key follows the code: a changed source file or preset gives every job a new key
(a development change never serves an old kit), and nothing but the files' paths and bytes
counts (compiled Python, file times and the folder's place do not)."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import weavecut
from weavecut.web import jobs
from weavecut.web.jobs import JobSpec, code_version
from weavecut.web.version import tree_hash

SPEC = JobSpec("kit", "subdivide", ("pentagon", "--levels=2"))


def _copy(tmp_path: Path) -> Path:
    package = Path(weavecut.__file__).resolve().parent
    return Path(shutil.copytree(package, tmp_path / "a" / "weavecut",
                                ignore=shutil.ignore_patterns("__pycache__")))


def test_a_changed_source_file_changes_the_hash(tmp_path):
    copy = _copy(tmp_path)
    before = tree_hash([copy])
    assert before == tree_hash([Path(weavecut.__file__).resolve().parent])  # the bytes only
    target = copy / "papermodel" / "strips.py"
    target.write_bytes(target.read_bytes() + b"\n# a changed comment\n")
    assert tree_hash([copy]) != before
    target.write_bytes(target.read_bytes()[:-len(b"\n# a changed comment\n")])
    assert tree_hash([copy]) == before
    (copy / "new_module.py").write_text("")
    assert tree_hash([copy]) != before


def test_compiled_python_and_file_times_do_not_count(tmp_path):
    copy = _copy(tmp_path)
    before = tree_hash([copy])
    (copy / "__pycache__").mkdir()
    (copy / "__pycache__" / "x.cpython-312.pyc").write_bytes(b"\0" * 16)
    (copy / "stray.pyc").write_bytes(b"\1")
    os.utime(copy / "mesh.py", (0, 0))
    assert tree_hash([copy]) == before


def test_a_changed_preset_changes_the_hash(tmp_path):
    copy = _copy(tmp_path)
    presets = Path(shutil.copytree(weavecut.presets.templates_dir(), tmp_path / "templates"))
    before = tree_hash([copy, presets])
    palette = next(iter(sorted((presets / "palettes").glob("*.toml"))))
    palette.write_text(palette.read_text().replace("#", "#", 1) + "\n")
    assert tree_hash([copy, presets]) != before
    # a file moved from one folder to the other is a change too
    assert tree_hash([copy, presets]) != tree_hash([presets, copy])


def test_the_key_follows_the_code_version(monkeypatch):
    assert code_version().startswith(weavecut.__version__ + "+")
    assert code_version() is code_version()  # computed once per process
    key = SPEC.key()
    monkeypatch.setattr(jobs, "code_version", lambda: weavecut.__version__ + "+" + "0" * 64)
    assert SPEC.key() != key
