"""Counts read as English in what the commands say: "1 copy", "1 sheet", never "1 copies" or
"sheet(s)" (text.counted); the star (no rotational symmetry: one copy of its module) and the
default puzzle (one sheet once its frame's hole takes pieces) are the cases that said so."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.cli import cli
from weavecut.text import counted

ROOT = Path(__file__).resolve().parents[1]
ONE_PLURAL = re.compile(r"(?<![\d.,])1 (?:copies|pages|sheets|strips|pieces|extras|files|"
                        r"colours|strands|octagons|enneagons)\b|\(s\)")


def test_counted_is_singular_for_one_only():
    assert [counted(n, "copy") for n in (0, 1, 2)] == ["0 copies", "1 copy", "2 copies"]
    assert counted(1, "sheet") == "1 sheet" and counted(3, "day") == "3 days"
    assert counted(2, "strip piece") == "2 strip pieces"


@pytest.mark.slow
def test_the_star_and_the_puzzle_say_one_in_the_singular(tmp_path):
    star = str(ROOT / "examples" / "star.svg")
    said = []
    for args in (["strands", star, "--cell", "10mm", "--levels", "1", "--tile-size", "21mm",
                  "-o", str(tmp_path / "star.pdf")],
                 ["puzzle", "--numbers", "-o", str(tmp_path / "pz")]):
        res = CliRunner().invoke(cli, args)
        assert res.exit_code == 0, res.output
        said.append(res.output)
    said.append((tmp_path / "pz" / "README.txt").read_text())
    assert "C1, 1 copy of a 31-strip module" in said[0]
    assert "separate: cut" in said[1] and ", 1 sheet, about" in said[1]
    assert [m[0] for text in said for m in ONE_PLURAL.finditer(text)] == []


def test_the_kit_benchmark_counts_in_the_singular(tmp_path):
    """benchmarks/bench_kits.py's page column: a one-sheet card kit, a one-page PDF."""
    from benchmarks.bench_kits import pages

    kit = tmp_path / "card"
    kit.mkdir()
    (kit / "strands-card-1.svg").write_text("<svg/>")
    (tmp_path / "one.pdf").write_bytes(b"%PDF-1.4 1 0 obj << /Type /Page /Parent 2 0 R >>")
    said = [pages(kit), pages(tmp_path / "one.pdf")]
    assert said == ["1 sheet, 1 file", "1 page"]
    (kit / "strands-assembly.pdf").write_bytes(b"%PDF")
    assert pages(kit) == "1 sheet, 2 files"
