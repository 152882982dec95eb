"""Guards of the command line that no test failed without (each disabled once by
``tests/hand_audit/guards.py``, #34): an option's value a person could type, and what must be
said about it, in one line, before any file is written."""

from __future__ import annotations

import pytest

from .helpers import files_under, refused, run

# arguments (OUT: a path in the test's folder, TMP: the folder), exit status, what the one
# line says
CASES = [
    (("fractal", "pentagon", "--levels", "3", "--curve", "-1:3"), 2,
     "'-1:3': level and edge must be >= 0"),
    (("fractal", "pentagon", "--levels", "3", "--curve", "2:-1"), 2,
     "'2:-1': level and edge must be >= 0"),
    (("fractal", "pentagon", "--levels", "3", "--curve", "5:1"), 2,
     "level 5 is beyond --levels 3"),
    (("levels", "pentagon", "--levels", "2", "--window", "1,2,3", "-o", "OUT.png"), 2,
     "'1,2,3' is not four numbers X0,Y0,X1,Y1"),
    (("levels", "pentagon", "--levels", "2", "--window", "0,0,nan,1", "-o", "OUT.png"), 2,
     "'0,0,nan,1' is not four numbers X0,Y0,X1,Y1"),
    (("levels", "pentagon", "--levels", "2", "--window", "1,0,0,1", "-o", "OUT.png"), 2,
     "'1,0,0,1': need X0 < X1 and Y0 < Y1"),
    (("levels", "pentagon", "--levels", "2", "--window", "0,1,1,1", "-o", "OUT.png"), 2,
     "'0,1,1,1': need X0 < X1 and Y0 < Y1"),
    (("levels", "pentagon", "--levels", "2"), 2, "give either -o FILE.png or --tiles FOLDER"),
    (("levels", "pentagon", "--levels", "2", "-o", "OUT.png", "--tiles", "OUT"), 2,
     "give either -o FILE.png or --tiles FOLDER"),
    (("figure", "edge-renders"), 2, "give an output file with -o"),
    (("figure",), 2, "give a figure NAME, or --list"),
    (("build", "weaves", "--dry-run", "--set", "levels"), 2, "'levels' is not KEY=VALUE"),
    (("build", "weaves", "--dry-run", "--set", " =3"), 2, "' =3' is not KEY=VALUE"),
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
     "dual of pentagon has no faces at level 1 (the scheme needs inner vertices or edges this "
     "mesh does not have); try another scheme or input"),
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
    (("strands", "pentagon-flower", "--tile-size", "3cm", "--size", "27cm", "-o", "TMP/s.pdf"),
     2, "'--size': give --tile-size or --size, not both"),
    (("subdivide", "dodecahedron", "--levels", "1", "-o", "TMP/d.svg"), 1,
     "dodecahedron is a surface in space (x, y, z vertices); a .svg drawing needs a flat mesh "
     "so far"),
    (("weave", "dodecahedron", "--levels", "1", "-o", "TMP/w.pdf"), 1,
     "dodecahedron is a surface in space (x, y, z vertices); a .pdf drawing needs a flat mesh "
     "so far"),
]


@pytest.mark.parametrize("args, status, says", CASES,
                         ids=[" ".join(a[:1] + a[3:5]) or a[0] for a, _, _ in CASES])
def test_a_bad_option_value_is_one_line_and_writes_nothing(tmp_path, args, status, says):
    out = str(tmp_path / "out")
    refused(run(*[a.replace("OUT", out).replace("TMP", str(tmp_path)) for a in args]), says,
            status=(status,))
    assert files_under(tmp_path) == set()


@pytest.mark.parametrize("body, says", [
    ('input = 3\nlevels = 1\noutput = "w.svg"\n', "job 1 (weave): input: expected a string"),
    ('input = "no-such-mesh.obj"\nlevels = 1\noutput = "w.svg"\n',
     "job 1 (weave): input 'no-such-mesh.obj' is neither a built-in input nor a file beside "
     "the recipe"),
])
def test_a_recipe_jobs_input_is_a_name_or_a_file_beside_it(tmp_path, body, says):
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "weave"\n' + body)
    refused(run("build", recipe, "-o", tmp_path / "out"), says)
    assert files_under(tmp_path) == {"r.toml"}


def test_a_recipe_page_size_given_as_a_number_is_refused(tmp_path):
    """A page is a name or WxH with units: a number (TOML lets one through) is a usage error
    of the job, not an internal error."""
    recipe = tmp_path / "r.toml"
    recipe.write_text('[[job]]\ncommand = "subdivide"\ninput = "pentagon"\nlevels = 1\n'
                      'output = "s.pdf"\npage = 5\n')
    refused(run("build", recipe, "-o", tmp_path / "out"), "job 1 (subdivide)",
            "5 is not a page size: use a4, a3, letter, a preset or WxH like 200x300mm")
    assert files_under(tmp_path) == {"r.toml"}


@pytest.mark.parametrize("output, says", [
    ("index.html", "job 2 (weave): output 'index.html' is weave-cut's page of the build"),
    ("sub/.weave-cut-manifest.json", "job 2 (weave): output 'sub/.weave-cut-manifest.json' is "
                                     "weave-cut's manifest"),
])
def test_a_recipe_job_never_writes_the_builds_page_or_a_manifest(tmp_path, output, says):
    """The build writes its kit page at the top of its folder and a manifest in each folder
    it writes: a job naming either is refused before any job runs (a job before it too)."""
    recipe = tmp_path / "r.toml"
    job = '[[job]]\ncommand = "weave"\ninput = "pentagon"\nlevels = 1\noutput = "{}"\n'
    recipe.write_text(job.format("first.svg") + job.format(output))
    refused(run("build", recipe, "-o", tmp_path / "out"), says)
    assert files_under(tmp_path) == {"r.toml"}


def test_a_path_is_too_long_only_past_the_file_systems_limits(tmp_path):
    """4,096 bytes of path and 255 of a name are allowed; one byte more of either is refused."""
    from weavecut.cli.outputs import NAME_MAX, PATH_MAX, too_long

    name = "n" * NAME_MAX
    assert too_long(tmp_path / name) is None
    assert "(this one 256)" in too_long(tmp_path / (name + "n"))
    head = str(tmp_path) + "/"
    rest = PATH_MAX - len(head)
    parts = [name] * (rest // (NAME_MAX + 1)) + ["n" * (rest % (NAME_MAX + 1) or 1)]
    path = head + "/".join(parts)
    path = path[:PATH_MAX] if len(path) > PATH_MAX else path + "n" * (PATH_MAX - len(path))
    assert len(path) == PATH_MAX and max(map(len, path.split("/"))) <= NAME_MAX
    assert too_long(path) is None
    assert "and a path 4,096" in too_long(path + "n")
