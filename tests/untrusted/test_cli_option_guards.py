"""The commands' own option checks and the output-path checks that no test failed without
(each disabled once by ``tests/hand_audit/guards.py``, #34): a combination of options a person
could type, refused in one line that says what to do, before any file is written."""

from __future__ import annotations

import pytest

from .helpers import files_under, refused, run

# arguments (TMP: the test's empty folder), exit status, what the one line says
CASES = [
    (("subdivide", "pentagon", "--levels", "1", "--scheme", "loop", "--no-smooth", "-o",
      "TMP/s.svg"), 2, "--no-smooth, --chirality, --centre and --project apply to --scheme snub"),
    (("stats", "dodecahedron", "--levels", "1", "--scheme", "loop"), 1,
     "dodecahedron is a surface in space; only --scheme snub subdivides surfaces so far"),
    (("weave", "pentagon", "--levels", "1"), 2,
     "give -o OUTPUT for a picture, or --json for the counts"),
    (("weave", "pentagon", "--levels", "2", "--outline-level", "2", "-o", "TMP/w.svg"), 2,
     "'--outline-level': must be below --levels 2"),
    (("weave", "pentagon", "--levels", "1", "-o", "TMP/w.glb"), 1,
     "pentagon is flat; a .glb woven model needs a surface in space"),
    (("weave", "pentagon", "--levels", "1", "--scheme", "dual", "-o", "TMP/w.svg"), 1,
     "dual of pentagon has no faces at level 1"),
    (("weave", "pentagon", "--levels", "1", "--scheme", "midedge", "-o", "TMP/w.svg"), 1,
     "the midedge weave of pentagon at level 1 has no tiles: no two faces glue into one; try "
     "--face-split or another scheme"),
    (("worker", "--queue", "http://127.0.0.1:6379/0"), 2,
     "'http://127.0.0.1:6379/0' is not a Redis URL like redis://HOST:PORT/DB"),
    (("strands", "pentagon-flower", "--preview", "--json", "-o", "TMP/look.svg"), 2,
     "--preview draws the pattern only; give it without --cutter, --laser-card and --json"),
    (("strands", "pentagon-flower", "--cutter", "silhouette", "--laser-card", "-o", "TMP/card"),
     2, "give --cutter (print and cut) or --laser-card, not both"),
    (("strands", "pentagon-flower", "--material", "poplar-3mm", "-o", "TMP/s.pdf"), 2,
     "--material goes with --laser-card"),
    (("strands", "pentagon-flower", "--formats", "svg", "-o", "TMP/s.pdf"), 2,
     "--formats goes with --laser-card"),
    (("strands", "pentagon-flower", "--laser-card", "--layout", "module", "-o", "TMP/card"), 2,
     "--laser-card cuts every strip once: leave --layout out"),
    (("strands", "pentagon-flower", "--size", "1001m", "-o", "TMP/s.pdf"), 2,
     "'1001m' is larger than a kilometre"),
    (("subdivide", "pentagon", "--levels", "1", "-o", ""), 2,
     "an empty path names no file or folder"),
    (("subdivide", "pentagon", "--levels", "1", "-o", "TMP/.weave-cut-manifest.json"), 2,
     "is weave-cut's manifest of the folder; choose another name"),
    (("subdivide", "pentagon", "--levels", "1", "-o", "TMP/new/"), 2,
     "is a folder, but here it names the one file written; give a file name"),
    (("puzzle", "pentagon", "--levels", "2", "-o", "TMP/kit.svg"), 2,
     "is named like a file, but here it is the folder the files go into; name it without "
     "'.svg'"),
]


@pytest.mark.parametrize("args, status, says", CASES,
                         ids=[" ".join(a[:1] + a[3:7]) for a, _, _ in CASES])
def test_a_bad_option_combination_is_one_line_and_writes_nothing(tmp_path, args, status,
                                                                  says):
    refused(run(*[a.replace("TMP", str(tmp_path)) for a in args]), says, status=(status,))
    assert files_under(tmp_path) == set()


def test_the_kit_page_never_replaces_an_output(tmp_path):
    refused(run("weave", "pentagon", "--levels", "1", "-o", tmp_path / "w.svg", "--html",
                tmp_path / "w.svg"), "'--html': the page would replace an output",
            status=(2,))
    assert (tmp_path / "w.svg").read_bytes().rstrip().endswith(b"</svg>")  # the drawing


def test_a_build_refuses_a_file_where_a_jobs_folder_goes(tmp_path):
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "puzzle"\ninput = "pentagon"\nlevels = 2\n'
                      'output = "kit"\n')
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "kit").write_text("mine")
    refused(run("build", recipe, "-o", tmp_path / "out"),
            "job 1 (puzzle): output: ", "is a file, but here -o is the folder the files go into")
    assert files_under(tmp_path) == {"r.toml", "out/kit"}
    assert (tmp_path / "out" / "kit").read_text() == "mine"


def test_a_shared_cut_larger_than_the_sheet_is_refused_in_shared_mode(tmp_path):
    """--mode shared asks for the one board only: on a smaller sheet that is a refusal saying
    what to do, not a folder of other files (--mode both writes the separate sheets)."""
    refused(run("puzzle", "pentagon", "--levels", "2", "--sheet", "100x100mm", "--mode",
                "shared", "-o", tmp_path / "kit"),
            "larger than the 100 x 100 mm sheet; use --mode separate (the frame is then split "
            "into parts) or a larger --sheet")
    assert files_under(tmp_path) == set()


def test_a_level_with_coordinates_too_small_for_floating_point_is_refused(tmp_path):
    """Faces 1e-160 across: their area centroids divide by areas of 1e-320, which floating
    point cannot hold; the level is refused with what to do, not written with NaN."""
    mesh = tmp_path / "tiny.obj"
    mesh.write_text("v 0 0\nv 1e-160 0\nv 1e-160 1e-160\nv 0 1e-160\nv 2e-160 0\n"
                    "f 1 2 3 4\nf 2 5 3\n")
    refused(run("subdivide", mesh, "--levels", "2", "--centre", "area", "-o",
                tmp_path / "t.svg"),
            "has coordinates that are not finite at level 2 (faces too small for --centre "
            "area?); scale the mesh up or use --centre vertex")
    assert files_under(tmp_path) == {"tiny.obj"}
