"""Every scheme on every built-in input, for subdivide, weave and stats: it works (a non-empty
mesh, a weave with tiles, strict JSON) or it is refused with a reason, never an internal error
(19 combinations were internal errors; dual of a single face wrote a mesh of 0 faces)."""

from __future__ import annotations

import numpy as np
import pytest

from weavecut import inputs
from weavecut.subdivision import SCHEMES

from .helpers import refused, run, strict_json, well_formed_xml

MATRIX = [(c, s, i) for c in ("subdivide", "weave", "stats") for s in sorted(SCHEMES)
          for i in inputs.INPUTS]


@pytest.mark.parametrize("command,scheme,name", MATRIX)
def test_works_or_is_refused_with_a_reason(tmp_path, command, scheme, name):
    for levels in (1, 2):
        out = tmp_path / f"{levels}.{ {'subdivide': 'json', 'weave': 'svg'}.get(command)}"
        args = [command, name, "--scheme", scheme, "--levels", levels]
        args += ["--json"] if command == "stats" else ["-o", out]
        result = run(*args)
        if result.exit_code != 0:
            refused(result)
            assert not out.exists()
            continue
        if command == "subdivide":
            mesh = strict_json(out.read_text())
            assert mesh["faces"], "an empty mesh is refused, never written"
            assert np.isfinite(np.array(mesh["vertices"], dtype=float)).all()
        elif command == "weave":
            assert well_formed_xml(out).findall(".//{*}path") or well_formed_xml(out).findall(
                ".//{*}polygon")
        else:
            assert all(row["faces"] > 0 for row in strict_json(result.output)["levels"])


def test_known_refusals_say_why(tmp_path):
    refused(run("subdivide", "pentagon", "--scheme", "dual", "--levels", 1, "-o",
                tmp_path / "m.obj"), "no faces at level 1")
    for scheme in ("midedge", "doo-sabin", "dual"):
        refused(run("weave", "pentagon", "--scheme", scheme, "--levels", 2, "-o",
                    tmp_path / "w.svg"), "pentagon")
    refused(run("weave", "pentagon", "--scheme", "midedge", "--levels", 2, "-o",
                tmp_path / "w.svg"), "no tiles")
    assert not list(tmp_path.iterdir())
