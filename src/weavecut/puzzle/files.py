"""The puzzle as Drawings: cut files (shared or separate), painting guides, the summary.

Coordinates: the shared cut sheet and both guides use one frame of reference, the frame's
bounding box moved to ``margin`` mm from the sheet's bottom-left corner, so a guide printed at
1:1 lies exactly on the cut sheet (the back guide mirrored left-right about the sheet's centre,
as the flipped board shows it).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import shapely
from numpy.typing import NDArray
from shapely import affinity

from .. import presets
from ..layout import cutpaths, nesting
from ..layout.drawing import (Drawing, Layer, Polygons, Polylines, Sheet, Style, Text,
                      polygons_from_shapely)
from ..errors import WeaveCutError
from .pieces import KIND_NAMES, UNPAINTED, Colouring, Puzzle, piece_halves

DEFAULT_LASER = "lightburn"
TRAVEL_SPEED = 300.0  # mm/s head moves between cuts, for the time estimate


@dataclass(frozen=True)
class Laser:
    """Colours and stroke widths a laser program expects per role (``templates/laser``)."""

    name: str
    styles: dict = field(default_factory=dict)

    def style(self, role: str) -> Style:
        entry = self.styles.get(role, {})
        return Style(entry.get("colour", "#000000"), float(entry.get("width", 0.01)))


def laser(name: str = DEFAULT_LASER) -> Laser:
    doc = presets.load("laser", name)
    return Laser(str(doc.get("name", name)),
                 {k: v for k, v in doc.items() if isinstance(v, dict)})


@dataclass(frozen=True)
class CutResult:
    """A cut Drawing plus what the summary needs (lengths in mm)."""

    drawing: Drawing
    cut_length: float
    travel_length: float
    n_paths: int
    n_sheets: int


def _lines(paths: list[NDArray], style: Style) -> Polylines:
    coords = np.concatenate(paths) if paths else np.zeros((0, 2))
    offsets = np.r_[0, np.cumsum([len(p) for p in paths])].astype(np.int64)
    return Polylines(coords, offsets, style)


def _ring_paths(polys) -> list[NDArray]:
    """Closed exterior and hole rings as closed polylines (first point repeated)."""
    out = []
    for poly in polys:
        out.append(np.asarray(poly.exterior.coords))
        out.extend(np.asarray(r.coords) for r in poly.interiors)
    return out


def placement(puzzle: Puzzle, margin: float = 10.0) -> tuple[float, float, NDArray]:
    """Sheet width, height and the shift that puts the frame ``margin`` mm from the corner."""
    x0, y0, x1, y1 = puzzle.outer.bounds
    return x1 - x0 + 2 * margin, y1 - y0 + 2 * margin, np.array([margin - x0, margin - y0])


def _number_texts(points: NDArray, angles: NDArray, size: float, style: Style) -> list[Text]:
    """Piece numbers 1..P centred on ``points``."""
    rad = np.radians(angles)
    dx, dy = np.sin(rad) * size / 2, -np.cos(rad) * size / 2  # baseline half a cap below
    return [Text(float(x + ex), float(y + ey), str(k + 1), size, "middle", float(a),
                 style.stroke or "#000000")
            for k, (x, y, ex, ey, a) in enumerate(zip(points[:, 0], points[:, 1], dx, dy,
                                                      angles))]


def ring_score_lines(puzzle: Puzzle) -> list[NDArray]:
    """Edges of the unclaimed ring hexagons that are not on the frame's hole (score lines)."""
    if not len(puzzle.ring):
        return []
    free = shapely.difference(shapely.union_all(shapely.get_exterior_ring(puzzle.ring)),
                              shapely.buffer(puzzle.hole.exterior, 1e-6))
    free = shapely.line_merge(free)
    parts = shapely.get_parts(free)
    return [np.asarray(p.coords) for p in parts if p.length > 1e-6]


def shared_cut(puzzle: Puzzle, las: Laser, numbers: bool = False, score_ring: bool = True,
               margin: float = 10.0, number_size: float = 3.0) -> CutResult:
    """One sheet, every shared edge cut once: inner trails, then the hole outline, then the
    frame's outer outline, in an order that shortens head travel (home: top-left)."""
    width, height, shift = placement(puzzle, margin)
    rings = shapely.get_exterior_ring(shapely.transform(puzzle.pieces, lambda xy: xy + shift))
    n = shapely.get_num_coordinates(rings) - 1
    coords = shapely.get_coordinates(rings)
    keep = np.ones(len(coords), dtype=bool)
    keep[np.cumsum(n + 1) - 1] = False
    graph = cutpaths.shared_edges(coords[keep], np.r_[0, np.cumsum(n)].astype(np.int64))
    home = (0.0, height)
    inner, here = cutpaths.order_paths(cutpaths.trails(graph, graph.uses > 1), home)
    hole, here = cutpaths.order_paths(cutpaths.trails(graph, graph.uses == 1), here)
    outer_ring = np.asarray(puzzle.outer.exterior.coords) + shift
    outer, _ = cutpaths.order_paths([outer_ring], here)
    paths = inner + hole + outer
    cut = las.style("cut")
    layers = [Layer("cut-1-inner", "cut", (_lines(inner, cut),)),
              Layer("cut-2-hole", "cut", (_lines(hole, cut),)),
              Layer("cut-3-outer", "cut", (_lines(outer, cut),))]
    layers += _extras(puzzle, las, shift, numbers, score_ring, number_size)
    meta = (("mode", "shared"),)
    drawing = Drawing((Sheet(width, height, tuple(layers), "puzzle shared cut"),),
                      "weave-cut puzzle: shared-edge cut", meta)
    return CutResult(drawing, cutpaths.path_length(paths),
                     cutpaths.travel_length(paths, home), len(paths), 1)


def _extras(puzzle: Puzzle, las: Laser, shift, numbers: bool, score_ring: bool,
            number_size: float) -> list[Layer]:
    layers = []
    if score_ring:
        lines = [p + shift for p in ring_score_lines(puzzle)]
        if lines:
            layers.append(Layer("score-ring", "score", (_lines(lines, las.style("score")),)))
    if numbers:
        at = shapely.get_coordinates(shapely.point_on_surface(puzzle.pieces)) + shift
        texts = _number_texts(at, np.zeros(len(at)), number_size, las.style("engrave"))
        layers.append(Layer("engrave-numbers", "engrave", tuple(texts)))
    return layers


def check_kerf(puzzle: Puzzle, kerf: float) -> None:
    """Refuse a kerf that would eat the smallest piece: it must stay below the piece's inner
    radius (2 area / perimeter, exact for polygons with an incircle)."""
    inner = 2 * shapely.area(puzzle.pieces) / shapely.length(puzzle.pieces)
    k = int(np.argmin(inner))
    if kerf >= inner[k]:
        raise WeaveCutError(f"a kerf of {kerf:g} mm is wider than piece {k} ({inner[k]:.3g} mm "
                            "inner radius); use a smaller --kerf or a larger --size")


def separate_cut(puzzle: Puzzle, las: Laser, kerf: float, sheet: tuple[float, float],
                 spacing: float = 2.0, numbers: bool = False, margin: float = 5.0,
                 number_size: float = 3.0) -> CutResult:
    """Every piece a closed outline offset by kerf/2, the frame (hole shrunk by kerf/2) first,
    all nested onto ``sheet``-sized sheets; per sheet: pieces and the frame's hole, then the
    frame's outer outline last."""
    spacing = max(spacing, kerf)
    frame = nesting.offset(np.array([puzzle.frame], dtype=object), kerf)
    parts = np.concatenate([frame, nesting.offset(puzzle.pieces, kerf)])
    placed_at = nesting.nest(parts, sheet, spacing, margin)
    placed = placed_at.apply(parts)
    cut, eng = las.style("cut"), las.style("engrave")
    sheets, total, travel, n_paths = [], 0.0, 0.0, 0
    label_at = shapely.get_coordinates(shapely.point_on_surface(puzzle.pieces))
    for s in range(placed_at.n_sheets):
        on = np.flatnonzero(placed_at.sheet == s)
        home = (0.0, sheet[1])
        frame_here = on[on == 0]
        inner_rings = [np.asarray(r.coords) for k in frame_here for r in placed[k].interiors]
        piece_rings = [np.asarray(placed[k].exterior.coords) for k in on[on > 0]]
        inner, here = cutpaths.order_paths(piece_rings + inner_rings, home)
        outer, _ = cutpaths.order_paths([np.asarray(placed[k].exterior.coords)
                                         for k in frame_here], here)
        paths = inner + outer
        total += cutpaths.path_length(paths)
        travel += cutpaths.travel_length(paths, home)
        n_paths += len(paths)
        layers = [Layer("cut-1-inner", "cut", (_closed(inner, cut),))]
        if outer:
            layers.append(Layer("cut-2-outer", "cut", (_closed(outer, cut),)))
        if numbers:
            pk = on[on > 0]
            pts = np.array([affinity.translate(affinity.rotate(
                shapely.Point(label_at[k - 1]), placed_at.angle[k], origin=(0, 0)),
                *placed_at.shift[k]).coords[0] for k in pk.tolist()]).reshape(-1, 2)
            texts = [Text(t.x, t.y, str(int(k)), t.size, t.anchor, t.angle, t.fill)
                     for t, k in zip(_number_texts(pts, placed_at.angle[pk], number_size, eng),
                                     pk.tolist())]
            layers.append(Layer("engrave-numbers", "engrave", tuple(texts)))
        sheets.append(Sheet(sheet[0], sheet[1], tuple(layers), f"sheet {s + 1}"))
    drawing = Drawing(tuple(sheets), "weave-cut puzzle: separate pieces",
                      (("mode", "separate"), ("kerf", f"{kerf:g} mm")))
    return CutResult(drawing, total, travel, n_paths, placed_at.n_sheets)


def _closed(paths: list[NDArray], style: Style) -> Polygons:
    """Closed rings (drop the repeated last point) in cutting order."""
    rings = [p[:-1] if len(p) > 1 and np.allclose(p[0], p[-1]) else p for p in paths]
    coords = np.concatenate(rings) if rings else np.zeros((0, 2))
    offsets = np.r_[0, np.cumsum([len(r) for r in rings])].astype(np.int64)
    return Polygons(coords, offsets, style)


def nested_parts(result: CutResult) -> list[NDArray[np.object_]]:
    """The cut rings of every sheet as shapely polygons (for checks)."""
    out = []
    for sheet in result.drawing.sheets:
        rings = [r for layer in sheet.layers if layer.role == "cut" for shape in layer.shapes
                 for r in shape.rings()]
        out.append(np.array([shapely.Polygon(r) for r in rings], dtype=object))
    return out


# --- painting guides --------------------------------------------------------------------------

def guide(puzzle: Puzzle, colouring: Colouring, side: str, numbers: bool = False,
          margin: float = 10.0) -> Drawing:
    """The front (level t-1 weave, two halves per piece) or back (level t weave, mirrored)
    painting guide at 1:1, registered to the shared cut sheet."""
    width, height, shift = placement(puzzle, margin)
    mirror = side == "back"

    def place(geoms):
        moved = shapely.transform(geoms, lambda xy: xy + shift)
        if mirror:
            moved = shapely.transform(moved, lambda xy: np.column_stack([width - xy[:, 0],
                                                                         xy[:, 1]]))
        return moved

    thin = Style("#555555", 0.25)
    layers = []
    if side == "front":
        halves = piece_halves(puzzle)
        # an enneagon's 'halves' are its one pentagon twice: draw it once (even-odd fills)
        one = shapely.equals(halves[:, 0], halves[:, 1])
        pick = np.column_stack([np.ones(len(one), dtype=bool), ~one]).ravel()
        layers.append(Layer("paint", "paint", (polygons_from_shapely(
            place(halves.ravel()[pick]), Style(None, 0.0),
            colouring.front.ravel()[pick].tolist()),)))
    else:
        layers.append(Layer("paint", "paint", (polygons_from_shapely(
            place(puzzle.pieces), Style(None, 0.0), colouring.back.tolist()),)))
    hexes = puzzle.hexagons[puzzle.hexagons != None]  # noqa: E711
    if len(hexes):  # the ring stays natural wood on both sides
        layers.append(Layer("ring-unpainted", "paint", (polygons_from_shapely(
            place(hexes), Style(None, 0.0, UNPAINTED)),)))
    frame = place(np.array([puzzle.frame], dtype=object))
    outlines = [polygons_from_shapely(frame, Style("#000000", 0.4))]
    if len(puzzle.ring):
        outlines.append(polygons_from_shapely(place(puzzle.ring), thin))
    layers.append(Layer("frame", "guide", tuple(outlines)))
    layers.append(Layer("pieces", "guide", (polygons_from_shapely(place(puzzle.pieces), thin),)))
    if numbers:
        at = shapely.get_coordinates(place(shapely.point_on_surface(puzzle.pieces)))
        layers.append(Layer("numbers", "label", tuple(_number_texts(
            at, np.zeros(len(at)), 2.5, Style("#000000")))))
    layers.append(Layer("registration", "guide", tuple(_registration(width, height, margin))))
    title = f"weave-cut puzzle: {side} painting guide (level {puzzle.levels - (side == 'front')}" \
            " weave)" + (", mirrored" if mirror else "")
    return Drawing((Sheet(width, height, tuple(layers), f"{side} guide"),), title)


def _registration(width: float, height: float, margin: float) -> list:
    """Crosshairs in the four corners (symmetric, so front and back register) and a label."""
    r = margin * 0.4
    pts = [(margin / 2, margin / 2), (width - margin / 2, margin / 2),
           (margin / 2, height - margin / 2), (width - margin / 2, height - margin / 2)]
    segs = np.array([[(x - r, y), (x + r, y), (x, y - r), (x, y + r)] for x, y in pts])
    coords = segs.reshape(-1, 2)
    return [Polylines(coords, np.arange(0, len(coords) + 1, 2, dtype=np.int64),
                      Style("#000000", 0.2))]


# --- summary ----------------------------------------------------------------------------------

def summary(puzzle: Puzzle, results: dict[str, CutResult], speed: float,
            colouring: Colouring | None = None) -> dict:
    """Pieces by type, cut length, sheets and estimated time per mode (plain data)."""
    counts = {name: int((puzzle.kinds == k).sum()) for k, name in enumerate(KIND_NAMES)}
    out = {"levels": puzzle.levels, "pieces": int(puzzle.n_pieces), "pieces_by_type": counts,
           "ring_hexagons_in_frame": int(len(puzzle.ring)),
           "frame_mm": [round(v, 1) for v in np.subtract(puzzle.outer.bounds[2:],
                                                         puzzle.outer.bounds[:2]).tolist()],
           "speed_mm_s": speed, "modes": {}}
    if colouring is not None:
        out["front_colours"] = len(set(colouring.front.ravel()) - {UNPAINTED})
        out["back_colours"] = len(set(colouring.back) - {UNPAINTED})
    for mode, r in results.items():
        seconds = r.cut_length / speed + r.travel_length / TRAVEL_SPEED
        out["modes"][mode] = {"cut_length_m": round(r.cut_length / 1000, 3),
                              "travel_m": round(r.travel_length / 1000, 3),
                              "paths": r.n_paths, "sheets": r.n_sheets,
                              "time_min": round(seconds / 60, 1)}
    return out


DEFAULT_MATERIAL = "poplar-3mm"


def material(name: str = DEFAULT_MATERIAL) -> dict:
    """A material preset (``templates/materials``) with lengths in mm: thickness, kerf,
    sheet (width, height) and cut_speed (mm/s)."""
    from ..units import page_size, to_mm

    doc = presets.load("materials", name)
    try:
        return {"name": str(doc.get("name", name)), "thickness": to_mm(doc["thickness"]),
                "kerf": to_mm(doc["kerf"]), "sheet": page_size(doc["sheet"]),
                "cut_speed": float(doc["cut_speed"])}
    except (KeyError, ValueError) as exc:
        raise presets.PresetError(f"material {name!r}: bad or missing {exc}") from exc


def split_sheets(drawing: Drawing) -> list[Drawing]:
    """One Drawing per sheet."""
    return [Drawing((s,), f"{drawing.title}, {s.name}", drawing.metadata) for s in drawing.sheets]


def summary_text(info: dict) -> str:
    """The summary as a few readable lines."""
    kinds = ", ".join(f"{n} {k}s" for k, n in info["pieces_by_type"].items())
    lines = [f"level {info['levels']} puzzle: {info['pieces']} pieces ({kinds}); "
             f"{info['ring_hexagons_in_frame']} ring hexagons stay in the frame; frame "
             f"{info['frame_mm'][0]:g} x {info['frame_mm'][1]:g} mm"]
    if "front_colours" in info:
        lines.append(f"colours: front {info['front_colours']}, back {info['back_colours']}")
    for mode, m in info["modes"].items():
        lines.append(f"{mode}: cut {m['cut_length_m']:.2f} m in {m['paths']} paths, travel "
                     f"{m['travel_m']:.2f} m, {m['sheets']} sheet(s), about {m['time_min']:g} min "
                     f"at {info['speed_mm_s']:g} mm/s")
    if "files" in info:
        lines.append("files: " + ", ".join(info["files"]))
    return "\n".join(lines)
