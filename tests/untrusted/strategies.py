"""Hypothesis strategies for untrusted input: recipe values and jobs, preset tables, option
strings; each mixes plausible values with the hostile ones that once got through."""

from __future__ import annotations

import json
import math

from hypothesis import strategies as st

COMMANDS = ["subdivide", "stats", "weave", "inputs", "convexity", "figure", "puzzle",
            "strands", "levels", "fractal", "build", "subdivid", "--help", ""]
KEYS = ["levels", "level", "scheme", "size", "no-smooth", "no_smooth", "centre", "chirality",
        "json", "palette", "outline-level", "style", "kerf", "sheet", "speed", "turn", "mode",
        "material", "laser", "window", "born", "curve", "output", "input", "command", "name",
        "-o", "--output", "help"]
HOSTILE_STRINGS = ["--help", "--output=/tmp/x", "-o", "-", "../x.svg", "../../.bashrc",
                   "/etc/passwd", "/tmp/weave-cut-fuzz.svg", "a/../../b.svg", ".", "..", "",
                   "nan", "inf", "1e400", "-1mm", "1e400x1e400", "5", "\x00", "\x1b[31m",
                   "caf\u00e9", "x" * 300, "pentagon", "square-grid:2x2", "ngon:-1",
                   "square-grid:99999x99999", "maritime-12", "poplar-3mm", "lightburn",
                   "../templates/palettes/puzzle.toml", "p.toml", "a\x00b.obj",
                   "x" * 300 + ".obj"]
OUTPUTS = ["x.svg", "x.json", "x.txt", "sub/x.svg", ".", "../x.svg", "/tmp/x.svg",
           "a/../../x.svg", "", "x" * 300 + ".svg", "link/x.svg", ".weave-cut-manifest.json",
           "r.toml", "m.obj", "x\x07.svg", "x\x00.svg", "x" * 300 + "/y.svg"]

scalars = st.one_of(
    st.sampled_from(HOSTILE_STRINGS), st.text(max_size=20),
    st.integers(-10, 50), st.integers(), st.floats(allow_nan=True, allow_infinity=True),
    st.booleans())
values = st.one_of(scalars, st.lists(scalars, max_size=3))


@st.composite
def jobs(draw) -> dict:
    job = {"command": draw(st.one_of(st.sampled_from(COMMANDS), st.text(max_size=8)))}
    if draw(st.booleans()):
        job["input"] = draw(st.one_of(st.sampled_from(HOSTILE_STRINGS), scalars))
    if draw(st.integers(0, 3)):
        job["output"] = draw(st.one_of(st.sampled_from(OUTPUTS), scalars))
    for key in draw(st.lists(st.sampled_from(KEYS), max_size=4, unique=True)):
        job[key] = draw(values)
    return job


PLAUSIBLE = {"subdivide": {"levels": st.integers(0, 2), "size": st.sampled_from(["50mm", 80]),
                           "scheme": st.sampled_from(["snub", "loop", "dual", "sqrt3"])},
             "stats": {"levels": st.integers(0, 2), "json": st.booleans()},
             "inputs": {"json": st.booleans()},
             "weave": {"levels": st.integers(1, 2), "palette": st.sampled_from(
                 ["maritime-12", "p.toml", "../p.toml", "okabe-ito"])}}


@st.composite
def plausible_jobs(draw) -> dict:
    """A job of a real command with its real keys; the output is still often hostile."""
    command = draw(st.sampled_from(sorted(PLAUSIBLE)))
    job = {"command": command, "output": draw(st.sampled_from(OUTPUTS))}
    if command != "inputs":
        job["input"] = draw(st.sampled_from(["pentagon", "square-grid:2x2", "m.obj",
                                             "../m.obj", *HOSTILE_STRINGS]))
    options = PLAUSIBLE[command]
    for key in draw(st.lists(st.sampled_from(sorted(options)), unique=True)):
        job[key] = draw(options[key])
    return job


def toml_value(value) -> str:
    """A TOML literal for a string, number, boolean or list (tomli_w is not a dependency)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return ("nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
                if math.isinf(value) else repr(value))
    if isinstance(value, int):
        return str(value)
    if isinstance(value, list):
        return "[" + ", ".join(map(toml_value, value)) + "]"
    return json.dumps(value)  # a TOML basic string (JSON's escapes are TOML's)


def toml_table(table: dict) -> str:
    return "".join(f"{json.dumps(k)} = {toml_value(v)}\n" for k, v in table.items())


@st.composite
def recipes(draw) -> str:
    text = "".join("[[job]]\n" + toml_table(job) for job in draw(
        st.lists(st.one_of(jobs(), plausible_jobs()), min_size=1, max_size=3)))
    return draw(st.sampled_from(["", "[recipe]\nname = \"fuzz\"\n"])) + text


LENGTHS = ["0.15mm", "3mm", "0", "-1mm", "1e400", "nan", "2in", "5km", "0.5", "mm", ""]
SHEETS = ["1300x900mm", "a4", "5", "1e400x1e400", "0x0", "100000x1mm", "axb", "10x10mm"]
COLOURS = ["#ff0000", "#00FF00", "red", "#fff", "#gggggg", "", "#0000ff0"]


def preset_values(strings):
    return st.one_of(st.sampled_from(strings), scalars, st.lists(scalars, max_size=2))


@st.composite
def materials(draw) -> dict:
    table = {"name": draw(st.one_of(st.just("m"), scalars)),
             "thickness": draw(preset_values(LENGTHS)), "kerf": draw(preset_values(LENGTHS)),
             "sheet": draw(preset_values(SHEETS)),
             "cut_speed": draw(st.one_of(st.floats(-1, 1e5), scalars))}
    drop = draw(st.lists(st.sampled_from(sorted(table)), max_size=2, unique=True))
    extra = draw(st.dictionaries(st.sampled_from(["cutspeed", "kerff", "colour"]), scalars,
                                 max_size=1))
    return {**{k: v for k, v in table.items() if k not in drop}, **extra}


@st.composite
def palettes(draw) -> dict:
    colours = st.lists(st.one_of(st.sampled_from(COLOURS), scalars), max_size=4)
    key = draw(st.sampled_from(["colours", "families", "both", "none"]))
    table = {}
    if key in ("colours", "both"):
        table["colours"] = draw(st.one_of(colours, scalars))
    if key in ("families", "both"):
        table["families"] = draw(st.one_of(st.lists(colours, max_size=3), scalars))
    return table


OPTION_STRINGS = st.one_of(
    st.sampled_from(["nan", "inf", "-inf", "1e400", "-1e400", "1e308", "0", "-0", "-1", "1",
                     "20", "1e-320", "0x0", "1e400x1e400", "nanxnan", "10x10mm", "a4", "huge",
                     "3mm", "2.5cm", "1in", "-3cm", "1e99km", "nanmm", "", " ", "1,2,3,4",
                     "0,0,1e308,1e308", "nan,0,1,1", "0,0,1,1"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.builds(lambda x, u: f"{x}{u}", st.floats(allow_nan=True, allow_infinity=True),
              st.sampled_from(["", "mm", "cm", "in", "km", "x10mm"])),
    st.text(max_size=12))
