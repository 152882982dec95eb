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


# --- hostile drawings -----------------------------------------------------------------------

NUMBERS = ["0", "1", "-1", "10", "50", "100", "3.5", "1e-9", "1e-300", "5e-324", "1e150",
           "-1e150", "1e200", "1e300", "-1e300", "1e308", "1e400", "nan", "inf", "-inf"]
numbers = st.one_of(st.sampled_from(NUMBERS), st.integers(-200, 200).map(str),
                    st.floats(allow_nan=False, allow_infinity=False).map(repr))
plain = st.integers(0, 100).map(str)  # most numbers of a drawing are ordinary


def _svg_number(draw) -> str:
    return draw(st.one_of(plain, plain, plain, plain, numbers))  # hostile one in five


@st.composite
def svg_shapes(draw) -> str:
    """One SVG shape with hostile numbers in its geometry and transform."""
    n = lambda: _svg_number(draw)  # noqa: E731
    kind = draw(st.sampled_from(["rect", "circle", "ellipse", "path", "polygon"]))
    if kind == "rect":
        shape = f'<rect x="{n()}" y="{n()}" width="{n()}" height="{n()}"/>'
    elif kind == "circle":
        shape = f'<circle cx="{n()}" cy="{n()}" r="{n()}"/>'
    elif kind == "ellipse":
        shape = f'<ellipse cx="{n()}" cy="{n()}" rx="{n()}" ry="{n()}"/>'
    elif kind == "polygon":
        corners = " ".join(f"{n()},{n()}" for _ in range(draw(st.integers(3, 6))))
        shape = f'<polygon points="{corners}"/>'
    else:
        d = [f"M{n()} {n()}"]
        for command in draw(st.lists(st.sampled_from("LCQAZ"), min_size=1, max_size=5)):
            d.append({"L": lambda: f"L{n()} {n()}",
                      "C": lambda: f"C{n()} {n()} {n()} {n()} {n()} {n()}",
                      "Q": lambda: f"Q{n()} {n()} {n()} {n()}",
                      "A": lambda: f"A{n()} {n()} {n()} {draw(st.sampled_from('01'))} "
                                   f"{draw(st.sampled_from('01'))} {n()} {n()}",
                      "Z": lambda: "Z"}[command]())
        shape = f'<path d="{" ".join(d)} Z"/>'
    if draw(st.booleans()):
        transform = draw(st.sampled_from(["scale({})", "translate({} {})", "rotate({})",
                                          "matrix({} {} {} {} {} {})", "skewX({})"]))
        shape = f'<g transform="{transform.format(*(n() for _ in range(6)))}">{shape}</g>'
    return shape


@st.composite
def hostile_svgs(draw) -> str:
    """An SVG with hostile numbers (transforms, arcs, curves, viewBox, size), nested
    ``<use>`` copies up to 12 deep and 12 wide, or many elements."""
    body = "".join(draw(st.lists(svg_shapes(), min_size=1, max_size=3)))
    levels = draw(st.one_of(st.just(0), st.just(0), st.integers(0, 12)))
    wide = draw(st.integers(1, 12))
    if levels:
        defs = f'<g id="u0">{body}</g>' + "".join(
            f'<g id="u{k}">' + f'<use href="#u{k - 1}"/>' * wide + "</g>"
            for k in range(1, levels + 1))
        body = f'<defs>{defs}</defs><use href="#u{levels}"/>'
    body *= draw(st.sampled_from([1, 1, 1, 2, 11_000]))
    size = draw(st.sampled_from(["100mm"] * 4 + ["10cm", "100", "1e300mm", "0mm", "nanmm",
                                                 "1e-300mm"]))
    box = draw(st.one_of(st.just(""), st.builds(lambda *v: f' viewBox="{" ".join(v)}"',
                                                plain, plain, numbers, numbers)))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}"{box}>'
            f"{body}</svg>")


@st.composite
def dxf_entities(draw) -> str:
    """One DXF entity of a kind the reader draws, with hostile numbers."""
    n = lambda: _svg_number(draw)  # noqa: E731
    kind = draw(st.sampled_from(["LINE", "CIRCLE", "ARC", "ELLIPSE", "LWPOLYLINE", "SPLINE"]))
    if kind == "LINE":
        return f"0\nLINE\n8\n0\n10\n{n()}\n20\n{n()}\n11\n{n()}\n21\n{n()}\n"
    if kind == "CIRCLE":
        return f"0\nCIRCLE\n8\n0\n10\n{n()}\n20\n{n()}\n40\n{n()}\n"
    if kind == "ARC":
        return f"0\nARC\n8\n0\n10\n{n()}\n20\n{n()}\n40\n{n()}\n50\n{n()}\n51\n{n()}\n"
    if kind == "ELLIPSE":
        return (f"0\nELLIPSE\n8\n0\n10\n{n()}\n20\n{n()}\n11\n{n()}\n21\n{n()}\n40\n{n()}\n"
                f"41\n{n()}\n42\n{n()}\n")
    if kind == "LWPOLYLINE":
        k = draw(st.integers(2, 5))
        return (f"0\nLWPOLYLINE\n100\nAcDbEntity\n8\n0\n100\nAcDbPolyline\n90\n{k}\n70\n1\n"
                + "".join(f"10\n{n()}\n20\n{n()}\n42\n{draw(st.one_of(st.just('0'), numbers))}\n"
                          for _ in range(k)))
    degree = draw(st.sampled_from([1, 2, 3, 3, 5, 10, 11, 50, 0, -1]))
    count = draw(st.integers(2, 8))
    knots = draw(st.one_of(
        st.just([0] * (max(degree, 0) + 1) + [1] * (count)),
        st.lists(numbers, min_size=count + max(degree, 0) + 1,
                 max_size=count + max(degree, 0) + 1)))
    return (f"0\nSPLINE\n100\nAcDbEntity\n8\n0\n100\nAcDbSpline\n70\n"
            f"{draw(st.sampled_from([0, 1]))}\n71\n{degree}\n72\n{len(knots)}\n73\n{count}\n"
            + "".join(f"40\n{k}\n" for k in knots)
            + "".join(f"10\n{n()}\n20\n{n()}\n30\n0\n" for _ in range(count)))


@st.composite
def hostile_dxfs(draw) -> str:
    """A DXF with hostile numbers in its entities and $INSUNITS, or many entities."""
    units = draw(st.sampled_from([0, 4, 4, 4, 4, 1, 6, 20, 8, -1, 9999]))
    body = "".join(draw(st.lists(dxf_entities(), min_size=1, max_size=4)))
    body *= draw(st.sampled_from([1, 1, 1, 2, 11_000]))
    return ("0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n"
            f"{units}\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n{body}0\nENDSEC\n0\nEOF\n")


def hostile_drawings():
    """(suffix, text) of a hostile SVG or DXF."""
    return st.one_of(hostile_svgs().map(lambda t: (".svg", t)),
                     hostile_dxfs().map(lambda t: (".dxf", t)))
