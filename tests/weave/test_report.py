"""The lineage summary counts every parent strand, with or without children."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from weavecut import inputs
from weavecut.cli import cli
from weavecut.subdivision import subdivide
from weavecut.weave.report import lineage_summary, weave_summaries
from weavecut.weave.snub_weave import snub_weaves


@pytest.mark.parametrize("name,levels", [("pentagon", 4), ("triangulated-ngon:24", 3),
                                         ("square-grid:3x3", 3)])
def test_every_parent_is_counted(name, levels):
    weaves = snub_weaves(subdivide(inputs.get(name), levels))
    for parent, row in zip(weaves, weave_summaries(weaves)[1:]):
        lin = row["lineage"]
        hist = {int(k): v for k, v in lin["children_per_parent"].items()}
        assert sum(hist.values()) == parent.n_strands == lin["parents"]
        # children: every strand with a parent, counted once
        assert sum(k * v for k, v in hist.items()) == row["strands"] - lin["orphans"]
        assert hist.get(0, 0) == lin["parents_without_children"]
        assert sum(lin["childless_parent_length_histogram"].values()) == hist.get(0, 0)


def test_parents_at_the_end_of_the_numbering_are_not_dropped():
    # the case: at level 3 of the triangulated 24-gon, parents without children sit
    # at the end of the parent numbering, which parent.max() + 1 dropped (48 of 72)
    weaves = snub_weaves(subdivide(inputs.get("triangulated-ngon:24"), 3))
    lin = weave_summaries(weaves)[2]["lineage"]
    assert lin["parents"] == 72
    assert lin["parents_without_children"] == 72 - len(np.unique(weaves[2].parent_strand))
    assert lin["parents_without_children"] > 0


def test_lineage_refuses_the_wrong_parent_weave():
    weaves = snub_weaves(subdivide(inputs.get("pentagon"), 3))
    with pytest.raises(ValueError, match="beyond"):
        lineage_summary(weaves[2], weaves[0])


def test_weave_json_has_lineage_and_nonconvex_counts():
    out = CliRunner().invoke(cli, ["weave", "pentagon", "--levels", "3", "--json"])
    data = json.loads(out.stdout)
    assert data["nonconvex_faces"] == 0
    assert "lineage" not in data["levels"][0]
    assert data["levels"][1]["lineage"]["parents"] == data["levels"][0]["strands"]
