"""Writers of coloured triangle models in space: OBJ (vertex colours) and PNG views (Pillow,
no GPU); glTF binary is :mod:`.gltf`'s.

A model is ``(vertices (N, 3), triangles (M, 3), colours (N, 3) uint8)``, one colour per
vertex. Paper is two-sided, so OBJ carries every triangle twice, once per side (with
its own vertices, so normals never cancel); the PNG renderer lights both sides.
"""

from __future__ import annotations

import io
import math

import numpy as np
from numpy.typing import NDArray
from PIL import Image

from ..errors import ExportError
from ..numeric import dot, matmul

# (azimuth, elevation) in degrees of the views of a PNG, left to right, top to bottom
VIEWS = ((20, 25), (110, 25), (200, 25), (290, -60))
SUPERSAMPLE = 2
LIGHT = np.array([-0.4, 0.5, 0.77])  # from the upper left, in view coordinates


def two_sided(vertices, triangles, colours):
    """The model with every triangle also facing the other way, on vertices of its own."""
    n = len(vertices)
    return (np.concatenate([vertices, vertices]), np.concatenate([triangles,
                                                                  triangles[:, ::-1] + n]),
            np.concatenate([colours, colours]))


def obj_bytes(vertices, triangles, colours, comments=()) -> bytes:
    """Wavefront OBJ with the common ``v x y z r g b`` vertex colours (MeshLab, Blender,
    trimesh read them), two-sided."""
    vertices, triangles, colours = two_sided(vertices, triangles, colours)
    lines = [f"# {c}".replace("\n", " ") for c in comments]
    rgb = colours / 255.0
    lines += [f"v {x!r} {y!r} {z!r} {r:.4f} {g:.4f} {b:.4f}"
              for (x, y, z), (r, g, b) in zip(vertices.tolist(), rgb.tolist())]
    lines += [f"f {a} {b} {c}" for a, b, c in (triangles + 1).tolist()]
    return ("\n".join(lines) + "\n").encode("utf-8")


def _rotation(azimuth: float, elevation: float) -> NDArray[np.float64]:
    """World to view: turn about z by ``azimuth``, then tilt by ``elevation``; the view looks
    along -z' (z' towards the viewer), y' up."""
    a, e = math.radians(azimuth), math.radians(elevation)
    spin = np.array([[math.cos(a), math.sin(a), 0], [-math.sin(a), math.cos(a), 0], [0, 0, 1]])
    # world z up -> view y up; world -y (after the spin) towards the viewer
    upright = np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], dtype=float)
    tilt = np.array([[1, 0, 0], [0, math.cos(e), -math.sin(e)], [0, math.sin(e), math.cos(e)]])
    return matmul(matmul(tilt, upright), spin)


def png_bytes(vertices, triangles, colours, size: int = 480, views=VIEWS,
              normals=None) -> bytes:
    """Views of the model side by side (two per row): flat-shaded, or smooth-shaded when
    ``normals`` (N, 3) gives every vertex its normal."""
    if not 16 <= size <= 4096:
        raise ExportError(f"a PNG view is 16 to 4096 pixels wide, got {size}")
    big = size * SUPERSAMPLE
    centre = (vertices.max(axis=0) + vertices.min(axis=0)) / 2
    radius = max(float(np.linalg.norm(vertices - centre, axis=1).max()), 1e-300)
    cols = 2
    rows = -(-len(views) // cols)
    sheet = Image.new("RGB", (cols * size, rows * size), "white")
    for k, view in enumerate(views):
        sheet.paste(_view(vertices - centre, triangles, colours, radius, big, view, normals)
                    .resize((size, size), Image.LANCZOS), ((k % cols) * size, (k // cols) * size))
    buf = io.BytesIO()
    sheet.save(buf, "PNG", optimize=False)
    return buf.getvalue()


def _view(vertices, triangles, colours, radius: float, big: int, view,
          normals=None) -> Image.Image:
    """One view: flat- or smooth-shaded triangles, orthographic, hidden surfaces removed by a
    depth buffer."""
    turn = _rotation(*view)
    p = matmul(vertices, turn.T)
    corners = p[triangles]  # (M, 3, 3)
    sun = np.asarray(LIGHT) / math.hypot(*LIGHT)
    xy = (corners[:, :, :2] / radius * 0.47 * big) * np.array([1, -1]) + big / 2
    front, tri, weights = _depth_buffer(xy, corners[:, :, 2], big)
    pixels = np.full((big * big, 3), 255.0)
    if normals is None:
        normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-300)[:, None]
        light = np.abs(dot(normal, sun))  # paper: lit on both sides
        pixels[front] = (colours[triangles].mean(axis=1) * (0.35 + 0.65 * light)[:, None])[tri]
    else:  # the shade of every corner, blended across the triangle
        light = 0.35 + 0.65 * np.abs(dot(matmul(normals, turn.T), sun))
        shaded = colours * light[:, None]
        pixels[front] = (shaded[triangles[tri]] * weights[:, :, None]).sum(axis=1)
    return Image.fromarray(np.round(pixels).astype(np.uint8).reshape(big, big, 3))


PAIRS_PER_CHUNK = 2_000_000  # (triangle, pixel) candidates rasterised at a time


def _depth_buffer(xy, depth, big: int):
    """(pixels, triangle, weights): the nearest triangle (largest depth) at every covered
    pixel, and the pixel centre's barycentric weights (K, 3) in it.

    Every triangle is tested at the pixel centres of its bounding box, chunk by chunk; the
    candidates inside it are interpolated and the nearest kept per pixel.
    """
    lo = np.clip(np.floor(xy.min(axis=1)), 0, big - 1).astype(np.int64)
    hi = np.clip(np.ceil(xy.max(axis=1)), 0, big - 1).astype(np.int64)
    w, h = hi[:, 0] - lo[:, 0] + 1, hi[:, 1] - lo[:, 1] + 1
    count = w * h
    zbuf = np.full(big * big, -np.inf)
    owner = np.full(big * big, -1, dtype=np.int64)
    where = np.zeros((big * big, 2))
    a, b, c = xy[:, 0], xy[:, 1], xy[:, 2]
    area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    ok = np.abs(area) > 1e-12
    bounds = np.searchsorted(np.cumsum(count), np.arange(0, count.sum(), PAIRS_PER_CHUNK))
    for first, last in zip(bounds, [*bounds[1:], len(count)]):
        tris = np.arange(first, last)
        tris = tris[ok[tris]]
        if not len(tris):
            continue
        tri = np.repeat(tris, count[tris])
        local = np.arange(len(tri)) - np.repeat(np.cumsum(count[tris]) - count[tris],
                                                count[tris])
        px = lo[tri, 0] + local % w[tri]
        py = lo[tri, 1] + local // w[tri]
        qx, qy = px + 0.5, py + 0.5
        # barycentric weights of the pixel centre
        wa = ((b[tri, 0] - qx) * (c[tri, 1] - qy) - (b[tri, 1] - qy) * (c[tri, 0] - qx)) / area[tri]
        wb = ((c[tri, 0] - qx) * (a[tri, 1] - qy) - (c[tri, 1] - qy) * (a[tri, 0] - qx)) / area[tri]
        wc = 1 - wa - wb
        inside = (wa >= 0) & (wb >= 0) & (wc >= 0)
        z = (wa * depth[tri, 0] + wb * depth[tri, 1] + wc * depth[tri, 2])[inside]
        pix, tri = (py * big + px)[inside], tri[inside]
        wab = np.column_stack([wa[inside], wb[inside]])
        # by pixel, then depth; of equally near triangles the first comes last, so that ties
        # go to the first triangle within a chunk as across chunks (where the nearer must be
        # strictly nearer): the picture does not depend on the chunks
        order = np.lexsort((-tri, z, pix))
        pix, z, tri, wab = pix[order], z[order], tri[order], wab[order]
        # the last of every pixel (the nearest); pixels are >= 0, so the last one differs
        # from -1 (and a chunk whose triangles cover no pixel centre keeps nothing)
        nearest = np.diff(pix, append=-1) != 0
        pix, z, tri, wab = pix[nearest], z[nearest], tri[nearest], wab[nearest]
        nearer = z > zbuf[pix]
        zbuf[pix[nearer]], owner[pix[nearer]] = z[nearer], tri[nearer]
        where[pix[nearer]] = wab[nearer]
    covered = np.flatnonzero(owner >= 0)
    wab = where[covered]
    return covered, owner[covered], np.column_stack([wab, 1 - wab.sum(axis=1)])
