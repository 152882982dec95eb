"""Presets (palettes, materials, laser, pages) and recipes are TOML checked against one declared
schema before any work; the text is bounded before the parser sees it."""

from __future__ import annotations

import importlib.util
import os
import threading
import time
from pathlib import Path

import pytest

from weavecut import presets
from weavecut.presets import schemas
from weavecut.schema import MAX_BYTES, MAX_DEPTH, read_toml, toml_depth

from .helpers import files_under, refused, run

MATERIAL = {"name": '"m"', "thickness": '"3mm"', "kerf": '"0.15mm"', "sheet": '"1300x900mm"',
            "cut_speed": "20.0"}


def toml(table: dict) -> str:
    return "".join(f"{k} = {v}\n" for k, v in table.items())


# a material key and value -> what the error says (the probe found each one used silently,
# or an internal error after 8 of 9 files were written)
MATERIAL_CASES = {
    ("kerf", '"-1mm"'): "kerf: '-1mm' must be >= 0 mm",
    ("kerf", "nan"): "kerf: nan is not a finite length",
    ("kerf", "inf"): "kerf: inf is not a finite length",
    ("kerf", '"0.15"'): "kerf: '0.15' has no unit",  # mm or cm? (issue #29)
    ("kerf", "0.15"): "kerf: '0.15' has no unit",
    ("kerf", "0"): None,  # zero in every unit
    ("kerf", '"6mm"'): "kerf: '6mm' must be <= 5 mm",
    ("kerf", "true"): "kerf: expected a length",
    ("sheet", "5"): "sheet: expected a size",
    ("sheet", '"1e400x1e400"'): "sheet:",
    ("sheet", '"0x900mm"'): "sheet:",
    ("sheet", '"20000x900mm"'): "larger than 10 m",
    ("cut_speed", "0"): "cut_speed: 0 must be > 0 mm/s",
    ("cut_speed", "nan"): "cut_speed: nan is not a finite number",
    ("cut_speed", '"fast"'): "cut_speed: expected a number",
    ("thickness", "[1, 2]"): "thickness: expected a length",
    ("cutspeed", "10"): "unknown key 'cutspeed' (did you mean 'cut_speed'?)",
}


@pytest.mark.parametrize("key,value", sorted(MATERIAL_CASES))
def test_material_values_are_checked_before_any_file_is_written(tmp_path, key, value):
    path = tmp_path / "m.toml"
    path.write_text(toml({**MATERIAL, key: value}))
    out = tmp_path / "pz"
    result = run("puzzle", "-o", out, "--levels", "2", "--mode", "shared", "--material", path)
    if MATERIAL_CASES[key, value] is None:
        assert result.exit_code == 0, result.output
        return
    refused(result, "m.toml", MATERIAL_CASES[key, value])
    assert not out.exists()


def test_missing_material_key_is_named(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(toml({k: v for k, v in MATERIAL.items() if k != "kerf"}))
    refused(run("puzzle", "-o", tmp_path / "pz", "--material", path), "missing key 'kerf'")


LASER = '[cut]\ncolour = "#ff0000"\n[score]\ncolour = "#0000ff"\n[engrave]\ncolour = "#000000"\n'


@pytest.mark.parametrize("text,needle", [
    ('[score]\ncolour = "#0000ff"\n[engrave]\ncolour = "#000000"\n', "missing key 'cut'"),
    (LASER.replace("#ff0000", "red"), "[cut] colour: 'red' is not a #rrggbb colour"),
    (LASER + "[cutt]\ncolour = '#ffffff'\n", "unknown key 'cutt' (did you mean 'cut'?)"),
    (LASER.replace('colour = "#ff0000"', 'colour = "#ff0000"\nwidth = -1'), "[cut] width"),
    (LASER.replace('colour = "#ff0000"', 'colour = "#ff0000"\nwidth = nan'), "[cut] width"),
    ("cut = 5\n" + LASER.split("[score]")[0].replace("[cut]\n", "") , "[cut]"),
])
def test_laser_presets(tmp_path, text, needle):
    path = tmp_path / "l.toml"
    path.write_text(text)
    refused(run("puzzle", "-o", tmp_path / "pz", "--laser", path), "l.toml", needle)
    assert not (tmp_path / "pz").exists()


@pytest.mark.parametrize("text,needle", [
    ('colours = ["red"]', "colours: item 1: 'red' is not a #rrggbb colour"),
    ('colours = "#ffffff"', "colours: expected a list"),
    ("colours = []", "colours: needs 1 to 256 items"),
    ('families = [["#ffffff"], "#000000"]', "families: item 2: expected a list"),
    ('colours = ["#ffffff"]\nfamilies = [["#000000"]]', "exactly one of"),
    ('name = 5\ncolours = ["#ffffff"]', "name: expected a string"),
    ("colours = [1, 2]", "item 1"),
    ('colours = ["#ffffff", "#000000"]\ncolour_names = ["white"]',
     "1 colour_names for 2 colours"),
])
def test_palette_presets(tmp_path, text, needle):
    path = tmp_path / "p.toml"
    path.write_text(text + "\n")
    refused(run("weave", "square-grid", "-n", "1", "--palette", path, "-o", tmp_path / "w.svg"),
            "p.toml", needle)
    assert not (tmp_path / "w.svg").exists()


def test_page_presets_and_bad_preset_names(tmp_path, monkeypatch):
    root = tmp_path / "templates"
    (root / "pages").mkdir(parents=True)
    (root / "pages" / "huge.toml").write_text("width = 1e400\nheight = 10\n")
    (root / "pages" / "ok.toml").write_text("width = '100mm'\nheight = '20cm'\n")
    (root / "pages" / "bare.toml").write_text("width = 100\nheight = 200\n")
    monkeypatch.setenv("WEAVECUT_TEMPLATES", str(root))
    refused(run("strands", "square-grid", "--page", "huge", "-o", tmp_path / "s.pdf"),
            status=(2,))
    with pytest.raises(presets.PresetError, match="unknown palette"):
        presets.load("palettes", "../pages/ok")
    assert presets.load("pages", "ok")["height"] == "20cm"
    refused(run("strands", "square-grid", "--page", "bare", "-o", tmp_path / "s.pdf"),
            "width: '100' has no unit", status=(2,))


def test_every_shipped_preset_passes_its_schema():
    for kind in (*schemas(), "recipes"):
        assert presets.names(kind), kind
        for name in presets.names(kind):
            presets.load(kind, name)  # raises on any problem
    for name in presets.names("recipes"):
        assert run("build", name, "--dry-run").exit_code == 0, name


# --- bounds before the parser -------------------------------------------------------------

def test_deep_dotted_key_is_refused_at_once(tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text("a" + ".a" * 50_000 + " = 1\n")  # once 62 s and 14.7 GB in tomllib
    refused(run("weave", "square-grid", "--palette", path, "-o", tmp_path / "w.svg"),
            f"nested deeper than {MAX_DEPTH}")
    recipe = tmp_path / "r.toml"
    recipe.write_text("[[job]]\ncommand = 'inputs'\nx = " + "[" * 5000 + "]" * 5000 + "\n")
    refused(run("build", recipe), "nested deeper")


@pytest.mark.parametrize("text,depth", [
    ("a = 1", 1), ("a.b.c = 1", 3), ("[a.b]\nc = 1", 3), ("[[a.b]]\nc = 1", 4),
    ("a = [[1]]", 3), ("a = {b = {c = 1}}", 3), ("t = {a.b = 1, c.d = 2, e.f = 3}", 3),
    ('"a.b" = "x.y.z"', 1), ("a = '''\n[[[[\n'''", 1), ("a = 1.5 # [[[[ .. ", 1),
    ("a = [1.5, 2.5, 3.5]", 2), ("[" + "a." * 30 + "b]", 32), ("[0]", 2),
])
def test_depth_counts_what_the_parser_nests(text, depth):
    assert toml_depth(text) == depth


def test_size_encoding_and_file_kind_are_bounded(tmp_path):
    big = tmp_path / "big.toml"
    big.write_text("# x\n" * (MAX_BYTES // 4 + 1))
    with pytest.raises(presets.PresetError, match="larger than"):
        read_toml(big, presets.PresetError)
    latin = tmp_path / "latin.toml"
    latin.write_bytes(b'name = "caf\xe9"\n')
    refused(run("weave", "square-grid", "--palette", latin, "-o", tmp_path / "w.svg"),
            "not UTF-8")
    fifo = tmp_path / "fifo.toml"
    os.mkfifo(fifo)
    done = []
    worker = threading.Thread(target=lambda: done.append(
        run("weave", "square-grid", "--palette", fifo, "-o", tmp_path / "w.svg")), daemon=True)
    worker.start()
    worker.join(timeout=30)  # a FIFO blocked reading forever before
    if not done:
        with open(fifo, "w"):  # unblock the reader so the test process can end
            time.sleep(0.1)
    assert done, "reading a FIFO preset blocked"
    refused(done[0], "not a regular file")
    refused(run("weave", "square-grid", "--palette", tmp_path, "-o", tmp_path / "w.svg"))
    assert files_under(tmp_path) == {"big.toml", "latin.toml", "fifo.toml"}


def test_a_preset_name_names_a_preset_and_not_a_path(tmp_path, monkeypatch):
    """A name without ".toml" is looked up among the presets of its kind only: a name that
    walks out of the folder ("../pages/ok"), an absolute one, or a spelling of a preset's
    path ("./mine", "../palettes/mine") is refused even though the file it would open is there (a path to a file
    must end in .toml, the explicit way)."""
    root = tmp_path / "templates"
    for kind in ("palettes", "pages"):
        (root / kind).mkdir(parents=True)
    (root / "palettes" / "mine.toml").write_text('colours = ["#102030"]\n')
    (root / "pages" / "ok.toml").write_text("width = '100mm'\nheight = '20cm'\n")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "evil.toml").write_text('colours = ["#ffffff"]\n')
    monkeypatch.setenv("WEAVECUT_TEMPLATES", str(root))
    assert presets.find("palettes", "mine") == root / "palettes" / "mine.toml"
    for name in ("../pages/ok", str(elsewhere / "evil"), "./mine", "../palettes/mine"):
        assert (root / "palettes" / f"{name}.toml").is_file()  # only the name check refuses
        with pytest.raises(presets.PresetError, match="unknown palette"):
            presets.find("palettes", name)
    assert presets.load("palettes", str(elsewhere / "evil.toml"))["colours"] == ["#ffffff"]


ROOT = Path(__file__).resolve().parents[2]
SINGULAR = {"palettes": "palette", "materials": "material", "laser": "laser",
            "pages": "page", "cutters": "cutter"}


@pytest.mark.parametrize("kind", sorted(SINGULAR))
def test_an_unknown_preset_name_says_its_kind_and_lists_the_folders_presets(kind):
    shipped = sorted(p.stem for p in (ROOT / "templates" / kind).glob("*.toml"))
    with pytest.raises(presets.PresetError) as caught:
        presets.find(kind, "no-such-preset")
    assert str(caught.value) == (f"unknown {SINGULAR[kind]} 'no-such-preset'; "
                                 f"choose one of {', '.join(shipped)}")


def test_a_folder_without_presets_says_none_was_found(tmp_path, monkeypatch):
    monkeypatch.setenv("WEAVECUT_TEMPLATES", str(tmp_path))
    with pytest.raises(presets.PresetError, match=r"unknown palette 'x'; choose one of "
                                                  r"\(none found\)$"):
        presets.find("palettes", "x")


def test_without_weavecut_templates_the_installed_presets_are_found(monkeypatch):
    """The package's own presets (``weavecut.templates``) when $WEAVECUT_TEMPLATES is unset:
    the same names as the checkout's templates/ folder; recipes also from examples/ where it
    is installed (``weavecut.examples``: not in an editable install made before it existed,
    nor from the sources on PYTHONPATH)."""
    monkeypatch.delenv("WEAVECUT_TEMPLATES", raising=False)
    examples = ({p.stem for p in (ROOT / "examples").glob("*.toml")}
                if importlib.util.find_spec("weavecut.examples") else set())
    for kind in (*SINGULAR, "recipes"):
        assert presets.names(kind) == sorted(
            {p.stem for p in (ROOT / "templates" / kind).glob("*.toml")}
            | (examples if kind == "recipes" else set())), kind
    assert presets.load("laser", "lightburn")["cut"]["colour"] == "#ff0000"


def test_a_preset_that_is_not_toml_is_a_preset_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("colours = [\n")
    with pytest.raises(presets.PresetError, match="bad.toml"):
        presets.load("palettes", str(bad))
