"""The README's findings section is `weave-cut findings` output: the fast rows are recomputed
here and must appear in the README verbatim; the slow rows must at least be there."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from weavecut.analysis import findings as fd
from weavecut.cli import cli

README = Path(__file__).resolve().parents[2] / "README.md"
BEGIN, END = "<!-- weave-cut findings: begin -->", "<!-- weave-cut findings: end -->"


def readme_table() -> list[str]:
    text = README.read_text(encoding="utf-8")
    block = text[text.index(BEGIN) + len(BEGIN):text.index(END)]
    return [line for line in block.splitlines() if line.startswith("|")]


@pytest.mark.slow
def test_readme_findings_are_the_command_output():
    result = CliRunner().invoke(cli, ["findings", "--fast", "--json"])
    assert result.exit_code == 0, result.output
    rows = [fd.Finding(**r) for r in json.loads(result.stdout)]
    assert rows and not any(r.slow for r in rows)
    table = readme_table()
    assert table[:2] == fd.markdown([]).splitlines()
    for line in fd.markdown_rows(rows):
        assert line in table, f"README's findings differ from the command:\n{line}"
    # every finding, slow ones too, has exactly one row, in the command's order
    topics = [line.split(" | ")[0].lstrip("| ") for line in table[2:]]
    expected = [r.topic for r in rows]
    assert [t for t in topics if t in expected] == expected
    assert len(topics) == len(fd.FINDINGS)
    # an independent oracle: the numbers measured once with `weave-cut convexity`
    convexity = {r.key: r.statement for r in rows}["convexity"]
    assert "ngon:24 72 at level 5, 600 at level 6" in convexity
    assert "triangulated-ngon:24 192 at level 5, 600 at level 6" in convexity
    assert re.search(r"square-grid 16 at level 6", convexity)
    assert "pentagon none" in convexity
