"""Checks over the Drawing that a maker can read every label: the figures ``strands --json``
reports and the tests hold.

A text is readable when it is at least ``MIN_CAP`` tall, reads upright (angle in (-90, 90]),
lies wholly on the one fill under its centre with nothing drawn over it, overlaps no other text,
has a contrast of at least ``MIN_CONTRAST`` with that fill, lies on the sheet inside its
margins, and, on a strip page, lies inside a strip's cut outline (strip labels) or outside the
printable box (page furniture, whose texts keep ``FURNITURE_GAP`` clear of each other). On
the assembly sheet every strand ID lies on its strand's fill,
or on a white plate whose leader line ends on that fill.
"""

from __future__ import annotations

import numpy as np
import shapely

from ..layout.contrast import MIN_CONTRAST, contrast_ratio
from ..layout.label_checks import PAPER, filled
from ..layout.label_checks import figures as label_figures
from ..layout.drawing import Polygons, Polylines, Sheet, Text
from ..layout.labels import MIN_CAP, text_box
from .pages import FURNITURE_GAP
from .slim import narrowest_feature

SLACK = 1e-6  # mm


def _fill_at(polys, fills, tree, point) -> str:
    """The fill drawn last at ``point`` (the paper's where nothing is)."""
    hits = [j for j in sorted(tree.query(point)) if polys[j].covers(point)] if tree else []
    return fills[hits[-1]] if hits else PAPER


def text_checks(sheet: Sheet, box=None, inner=None, strands=None, cuts=None) -> list[dict]:
    """One record per text: size, contrast, and the rules it breaks (empty when readable).

    ``box`` is the printable box of a strip page: texts of the "labels" layer must then lie inside
    a cut outline, every other text (the page furniture) outside the box and ``FURNITURE_GAP``
    clear of the others. ``inner`` (x0, y0, x1, y1): the sheet inside
    its margins, where every text must lie. ``strands`` maps a strand's ID to its fill: a text of
    the "ids" layer (the assembly sheet) naming a strand must lie on that fill, or on a white
    plate whose leader line ends on it. ``cuts``: the strips' cut outlines, where the sheet
    prints none (print and cut), else those of its cut layers."""
    polys, fills = filled(sheet)
    tree = shapely.STRtree(polys) if polys else None
    if cuts is None:
        cuts = [g for layer in sheet.layers if layer.role == "cut" for s in layer.shapes
                if isinstance(s, Polygons) for g in s.to_shapely().tolist()]
    texts = [(layer.name, t) for layer in sheet.layers for t in layer.shapes
             if isinstance(t, Text)]
    boxes = [text_box(t) for _, t in texts]
    text_tree = shapely.STRtree(boxes) if boxes else None
    leaders = [(line[0], line[-1]) for layer in sheet.layers for s in layer.shapes
               if isinstance(s, Polylines) for line in s.lines() if len(line) == 2]
    out = []
    for i, ((layer, t), b) in enumerate(zip(texts, boxes)):
        broken = []
        if t.size < MIN_CAP - 1e-9:
            broken.append("small")
        if not -90.0 < t.angle <= 90.0 + 1e-9:
            broken.append("upside down")
        centre = b.centroid
        below, fill = -1, PAPER
        hits = sorted(tree.query(b)) if tree is not None else []
        for j in hits:
            if polys[j].covers(centre):
                below, fill = j, fills[j]
        if below >= 0 and not polys[below].buffer(SLACK).covers(b):
            broken.append("crosses its fill's edge")
        if any(j > below and shapely.intersection(polys[j], b).area > SLACK for j in hits):
            broken.append("under another shape")
        others = [j for j in text_tree.query(b) if j != i] if text_tree is not None else []
        if any(shapely.intersection(boxes[j], b).area > SLACK for j in others):
            broken.append("overlaps a text")
        contrast = contrast_ratio(t.fill, fill)
        if contrast < MIN_CONTRAST:
            broken.append("low contrast")
        if inner is not None and not shapely.box(*inner).buffer(SLACK).covers(b):
            broken.append("off the sheet")
        if strands is not None and layer == "ids" and t.text in strands:
            want = strands[t.text]
            on = fill == want or (below >= 0 and fill == PAPER and any(
                _fill_at(polys, fills, tree, shapely.Point(far)) == want
                for near, far in leaders if polys[below].distance(shapely.Point(near)) < 1e-6))
            if not on:
                broken.append("outside its strand")
        if box is not None and layer != "labels" and any(
                texts[j][0] != "labels" and boxes[j].distance(b) < FURNITURE_GAP - SLACK
                for j in text_tree.query(b.buffer(FURNITURE_GAP)) if j != i):
            broken.append("touches a text")
        if box is not None:
            inside = shapely.box(*box).buffer(SLACK)
            if layer == "labels" and not any(c.buffer(SLACK).covers(b) for c in cuts):
                broken.append("outside its strip")
            if layer != "labels" and inside.intersection(b).area > SLACK:
                broken.append("furniture on the strips")
        out.append({"text": t.text, "size": t.size, "contrast": contrast, "broken": broken})
    return out


def sheet_checks(book, n: int) -> list[dict]:
    """:func:`text_checks` of page ``n`` (1-based) of a strand book, with the rules that page
    has: on a strip page its printable box, on the assembly sheet (page 1) and the pages naming
    the strands it has no room for the strands' fills."""
    area = book.area
    inner = (area.margin, area.margin, area.width - area.margin, area.height - area.margin)
    named = n == 1 or n in getattr(book, "id_pages", ())
    strands = dict(zip(book.plan.labels, book.colours)) if named else None
    strip = n in book.strip_pages
    cuts = [p.cut for k, p in book.pieces if k == n] or None  # none printed for print and cut
    return text_checks(book.drawing.sheets[n - 1], area.box if strip else None, inner, strands,
                       cuts if strip else None)


def report(book) -> dict:
    """What ``strands --json`` reports: pages, ink, smallest label, contrast (at the label's
    centre, and the least over everything under its box: ``label_checks``), the smallest gap
    between two labels, violations, label tabs, under-crossing names left off the strips, the
    slimmest piece (the narrowest neck, sliver or notch of any strip's cut outline,
    :func:`.strips.narrowest_feature`)."""
    records = []
    for n, sheet in enumerate(book.drawing.sheets, start=1):
        records += sheet_checks(book, n)
    return {
        "pages": {"strip": len(book.strip_pages), "extra": len(book.extra_pages),
                  "total": len(book.drawing.sheets)},
        "ink_fraction": round(book.ink, 3),
        "smallest_text_mm": round(min((r["size"] for r in records), default=0.0), 2),
        "smallest_contrast": round(min((r["contrast"] for r in records), default=21.0), 2),
        **{k: v for k, v in label_figures(book.drawing.sheets).items()
           if k in ("min_label_contrast", "min_label_gap_mm")},
        "label_violations": sum(bool(r["broken"]) for r in records),
        "label_tabs": sum(p.flap is not None for _, p in book.pieces),
        "names_left_out": sum(len(p.left_out) for _, p in book.pieces),
        "slimmest_piece_mm": round(float(narrowest_feature([p.cut for _, p in book.pieces]).min(
            initial=np.inf)), 2) if book.pieces else None,
        "tile_size_mm": round(book.tile_size, 2),
        "strip_width_mm": round(book.strip_width, 1),
        "warnings": list(book.warnings),
    }

