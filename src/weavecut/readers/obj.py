"""Wavefront OBJ meshes: ``v`` and ``f`` statements read a piece of whole lines at a time
(``CHUNK`` bytes: their scratch arrays stay in the processor's cache) with ``obj_tokens``;
a flat mesh drawn in another axis plane is turned into the xy-plane. Messages count faces and
vertices from 1 and give the line, as OBJ users count."""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from .. import readers
from ..errors import MeshFileError
from ..mesh import Mesh, Numbering, check_structure
from .obj_tokens import Tokens, statement_key

_IGNORED = (b"vt", b"vn", b"vp", b"o", b"g", b"s", b"usemtl", b"mtllib", b"l")
CHUNK = 2**18  # bytes of whole lines parsed at once: their scratch arrays stay in the cache


def _line_chunks(data: bytes):
    """``data`` in pieces of about ``CHUNK`` bytes that end at line feeds (views, no copies),
    each with whether it holds a ``#``."""
    a, view = 0, memoryview(data)
    while a < len(data):
        b = data.find(b"\n", a + CHUNK - 1) + 1 or len(data)
        yield view[a:b], data.find(b"#", a, b) >= 0
        a = b



@dataclass
class _Part:
    """The ``v`` and ``f`` statements of a piece of an OBJ file."""

    v_line: np.ndarray
    points: np.ndarray  # (V, 3)
    f_line: np.ndarray
    sizes: np.ndarray
    corners: np.ndarray  # 0-based
    wrong_index: str  # the first face index that refers to no vertex, or ""


def parse_obj(data: bytes) -> tuple[Mesh, Numbering, str]:
    """Mesh, 1-based numbering with face lines, and a remark about the plane ("" if none).

    The text is parsed a piece at a time; a bad line raises at once (lines come in order), a
    face index that refers to no vertex once every line is known good.
    """
    parts, n_lines, n_vertices, n_faces = [], 0, 0, 0
    for chunk, comments in _line_chunks(data):
        tok = Tokens(chunk, n_lines, comments)
        parts.append(_obj_part(tok, n_vertices))
        n_lines += tok.n_lines
        n_vertices += len(parts[-1].v_line)
        n_faces += len(parts[-1].f_line)
        if n_faces > readers.MAX_FACES or n_vertices > readers.MAX_VERTICES:
            raise MeshFileError(f"more than {readers.MAX_FACES:,} faces or "
                                f"{readers.MAX_VERTICES:,} vertices by line {n_lines:,}; "
                                "weave-cut reads at most that")
    if not n_faces:
        raise MeshFileError("no faces ('f' lines) found")
    wrong = [p.wrong_index for p in parts if p.wrong_index]
    if wrong:
        raise MeshFileError(wrong[0])
    join = lambda name: np.concatenate([getattr(p, name) for p in parts])  # noqa: E731
    vertices, remark = _in_plane(join("points"), join("v_line"))
    mesh = Mesh.trusted(vertices, np.concatenate([[0], np.cumsum(join("sizes"))]),
                        join("corners"))
    numbering = Numbering(first=1, face_lines=join("f_line"))
    check_structure(mesh, numbering)
    return mesh, numbering, remark


def _obj_part(tok: Tokens, n_vertices: int) -> _Part:
    """The statements of one piece, whose text follows ``n_vertices`` vertices; raises
    MeshFileError at its first bad line."""
    single = tok.end[tok.first] - tok.start[tok.first] == 1
    tag = tok.buf[tok.start[tok.first]]
    is_v, is_f = single & (tag == ord("v")), single & (tag == ord("f"))
    errors: list[tuple[int, int, str]] = []  # (line, rank on the line, message)
    other = np.flatnonzero(~(is_v | is_f))
    if len(other):
        other = other[~np.isin(tok.keys(tok.first[other]),
                               [statement_key(t) for t in _IGNORED])]
    if len(other):  # unknown statements
        i = other[0]
        errors.append((tok.line[i], 0, f"line {tok.line[i]}: unknown OBJ statement "
                                       f"{tok.text(tok.first[i])!r}"[:200]))
    v_line, f_line = tok.line[is_v], tok.line[is_f]
    points = _obj_vertices(tok, tok.first[is_v], tok.count[is_v] - 1, v_line, errors)
    sizes = tok.count[is_f] - 1
    indices = _obj_faces(tok, tok.first[is_f], sizes, f_line, errors)
    if errors:
        raise MeshFileError(min(errors)[2])
    wrong = ""
    if not len(indices) or (indices.min() > 0 and indices.max()
                           <= n_vertices + np.searchsorted(v_line, f_line[0])):
        return _Part(v_line, points, f_line, sizes, (indices - 1).astype(np.int32), wrong)
    seen = np.repeat(n_vertices + np.searchsorted(v_line, f_line), sizes)  # defined before
    bad = np.flatnonzero((indices == 0) | (np.abs(indices) > seen))
    if len(bad):
        k = bad[0]
        f = int(np.searchsorted(np.cumsum(sizes), k, side="right"))
        wrong = (f"line {f_line[f]}: face index {indices[k]} refers to no vertex "
                 f"({seen[k]} defined so far)")
    corners = np.where(indices > 0, indices - 1, seen + indices).astype(np.int32)
    return _Part(v_line, points, f_line, sizes, corners, wrong)


def _obj_vertices(tok: Tokens, first, n_numbers, lines, errors) -> np.ndarray:
    """(V, 3) coordinates of the ``v`` lines (z = 0 when left out); appends line errors."""
    wrong = np.flatnonzero((n_numbers < 2) | (n_numbers > 4))
    if len(wrong):
        i = wrong[0]
        errors.append((lines[i], 0, f"line {lines[i]}: a vertex needs x y [z], got "
                                    f"{n_numbers[i]} numbers"))
    tokens = first[:, None] + 1 + np.arange(3)
    if (n_numbers == 3).all():  # x y z on every line
        values, bad = tok.floats(tokens.ravel())
        points, used = values.reshape(-1, 3), np.ones(tokens.shape, dtype=bool)
    else:
        used = np.arange(3) < np.clip(n_numbers, 0, 3)[:, None]
        used[wrong] = False
        points = np.zeros((len(first), 3))
        values, bad = tok.floats(tokens[used])
        points[used] = values
    if bad is not None:
        i = np.flatnonzero(used.ravel())[bad] // 3
        errors.append((lines[i], 1, f"line {lines[i]}: vertex coordinates must be numbers"))
    infinite = np.flatnonzero(~np.isfinite(points).all(axis=1))
    if len(infinite):
        i = infinite[0]
        errors.append((lines[i], 2, f"line {lines[i]}: vertex coordinate is not finite"))
    return points


def _obj_faces(tok: Tokens, first, sizes, lines, errors) -> np.ndarray:
    """Vertex indices of the ``f`` lines as written (``i/t/n`` gives i); appends line errors
    (an index of more than 16 digits is too large)."""
    plain = _plain_indices(tok, first, sizes) if len(first) else None
    if plain is not None:
        return plain
    token = np.repeat(first + 1 - np.cumsum(sizes) + sizes, sizes) + np.arange(sizes.sum())
    start, end = tok.start[token], tok.end[token]
    slash = np.flatnonzero(tok.buf == ord("/"))
    if len(slash):
        after = slash[np.minimum(np.searchsorted(slash, start), len(slash) - 1)]
        end = np.where((after >= start) & (after < end), after, end)
    values, bad, too_long = tok.ints(start, end)
    face = np.cumsum(sizes)
    if bad.any():
        i = int(np.searchsorted(face, np.flatnonzero(bad)[0], side="right"))
        errors.append((lines[i], 0, f"line {lines[i]}: face indices must be whole numbers"))
    if too_long.any():
        k = int(np.flatnonzero(too_long)[0])
        i = int(np.searchsorted(face, k, side="right"))
        number = tok.buf[start[k]:end[k]][:41].tobytes().decode()
        number = number if len(number) <= 40 else number[:37] + "..."
        errors.append((lines[i], 1, f"line {lines[i]}: face index {number} is too large"))
    return values


def _plain_indices(tok: Tokens, first, sizes) -> np.ndarray | None:
    """The indices of ``f`` lines that follow one another and hold nothing but whole numbers
    of up to 16 bytes, read by numpy's C parser; None for any other lines (it stops at the
    first byte that continues no number and is no space, and warns)."""
    t0, t1 = first[0], first[-1] + sizes[-1] + 1
    if t1 - t0 != len(first) + sizes.sum() or (tok.end[t0:t1] - tok.start[t0:t1]).max() > 16:
        return None
    a = tok.start[t0]
    text = tok.buf[a:tok.end[t1 - 1]].copy()
    text[tok.start[first] - a] = ord(" ")  # the statements
    with warnings.catch_warnings():  # numpy 2.4 raises where a number ends in other bytes,
        warnings.simplefilter("error")  # older versions warn (and may split "1-2": counted)
        try:
            values = np.fromstring(text.tobytes(), dtype=np.int64, sep=" ")
        except (DeprecationWarning, ValueError):
            return None
    return values if len(values) == sizes.sum() else None


# the axis each plane is constant in, its name, and (u, v) seen from the positive axis
_PLANES = ((2, "xy-plane as (x, y)", lambda x, y, z: (x, y)),
           (1, "xz-plane as (x, -z), seen from +y", lambda x, y, z: (x, 0.0 - z)),
           (0, "yz-plane as (y, z), seen from +x", lambda x, y, z: (y, z)))


def _in_plane(points: np.ndarray, lines: np.ndarray) -> tuple[np.ndarray, str]:
    """(V, 2) coordinates in the axis-aligned plane the vertices lie in, and a remark; (V, 3)
    coordinates, and no remark, for a surface in space.

    A plane z = c is read as (x, y); y = c (Blender's ground plane, as its OBJ export
    writes it) as (x, -z), and x = c as (y, z): each seen from the positive axis, so
    counter-clockwise faces stay counter-clockwise and nothing is mirrored.
    """
    for axis, plane, project in _PLANES:
        c = points[:, axis]
        if (c == c[:1]).all():
            vertices = np.column_stack(project(*points.T))
            if axis == 2 and not c[:1].any():
                return vertices, ""
            return vertices, (f"all vertices have {'xyz'[axis]} = {float(c[0])!r}; "
                              f"read in the {plane}")
    return points, ""  # a surface in space

