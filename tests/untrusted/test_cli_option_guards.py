"""Guards of the command line that no test failed without and that need more than one
command line (``test_cli_guards`` holds those that do not; each disabled once by
``tests/hand_audit/guards.py``, #34): a refusal in one line that says what to do, and nothing
written but what the refused run had already finished."""

from __future__ import annotations

from .helpers import files_under, refused, run


def test_the_kit_page_never_replaces_an_output(tmp_path):
    """A page named as -o is refused before any work (nothing written); a page named as a
    file the command writes into its folder is refused once the files are known."""
    refused(run("weave", "pentagon", "--levels", "1", "-o", tmp_path / "w.svg", "--html",
                tmp_path / "." / "w.svg"), "'--html': -o writes ", "give each output its own name",
            status=(2,))
    assert files_under(tmp_path) == set()
    refused(run("puzzle", "pentagon", "--levels", "2", "-o", tmp_path / "kit", "--html",
                tmp_path / "kit" / "README.txt"), "'--html': the page would replace an output",
            status=(2,))
    assert "jigsaw puzzle" in (tmp_path / "kit" / "README.txt").read_text()  # the kit's


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
