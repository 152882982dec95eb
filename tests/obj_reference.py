"""A line-by-line OBJ reader that follows weave-cut's rules one statement at a time: the oracle
for the vectorised reader in ``weavecut.readers.obj``."""

from __future__ import annotations

import math
import re

import numpy as np

from weavecut.errors import MeshError
from weavecut.mesh import Mesh, Numbering, check_structure

IGNORED = {b"vt", b"vn", b"vp", b"o", b"g", b"s", b"usemtl", b"mtllib", b"l"}


class Refused(Exception):
    pass


def read(data: bytes) -> tuple[np.ndarray, list[list[int]], str]:
    """(vertices (V, 2) or (V, 3), 0-based faces, remark) or raise Refused(message)."""
    try:
        return _read(data)
    except MeshError as exc:  # the structure check, shared with the reader
        raise Refused(str(exc)) from None


def _read(data: bytes):
    text = data.replace(b"\r\n", b"\n").replace(b"\r", b"\n")
    points, faces, face_lines, v_lines, seen = [], [], [], [], []
    for n, line in enumerate(text.split(b"\n"), start=1):
        parts = [p for p in re.split(rb"[ \t\v\f]+", line.split(b"#")[0]) if p]
        if not parts:
            continue
        tag, args = parts[0], parts[1:]
        if tag == b"v":
            if not 2 <= len(args) <= 4:
                raise Refused(f"line {n}: a vertex needs x y [z], got {len(args)} numbers")
            try:
                xyz = [_float(a) for a in args[:3]]
            except ValueError:
                raise Refused(f"line {n}: vertex coordinates must be numbers") from None
            if not all(map(math.isfinite, xyz)):
                raise Refused(f"line {n}: vertex coordinate is not finite")
            points.append((xyz + [0.0])[:3])
            v_lines.append(n)
        elif tag == b"f":
            numbers = [a.split(b"/")[0] for a in args]
            if not all(re.fullmatch(rb"[+-]?[0-9]+", a) for a in numbers):
                raise Refused(f"line {n}: face indices must be whole numbers")
            for a in numbers:
                if len(a.lstrip(b"+-")) > 16:
                    shown = a.decode() if len(a) <= 40 else a[:37].decode() + "..."
                    raise Refused(f"line {n}: face index {shown} is too large")
            faces.append([int(a) for a in numbers])
            face_lines.append(n)
            seen.append(len(points))
        elif tag not in IGNORED:
            shown = re.sub(rb"[\x00-\x08\x0e-\x1f]", b"\x7f", tag).decode("utf-8", "ignore")
            raise Refused(f"line {n}: unknown OBJ statement {shown!r}"[:200])
    if not faces:
        raise Refused("no faces ('f' lines) found")
    corners = []
    for face, line, known in zip(faces, face_lines, seen):
        for i in face:
            if i == 0 or abs(i) > known:
                raise Refused(f"line {line}: face index {i} refers to no vertex "
                              f"({known} defined so far)")
            corners.append(i - 1 if i > 0 else known + i)
    vertices, remark = _plane(np.array(points, dtype=float).reshape(-1, 3), v_lines)
    sizes = [len(f) for f in faces]
    mesh = Mesh.trusted(vertices, np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
                        np.array(corners, dtype=np.int32))
    check_structure(mesh, Numbering(first=1, face_lines=np.array(face_lines)))
    return vertices, mesh.faces(), remark


def _float(token: bytes) -> float:
    if re.search(rb"[\x00-\x1f\x7f]", token):
        raise ValueError(token)
    return float(token)


def _plane(p: np.ndarray, lines: list[int]) -> tuple[np.ndarray, str]:
    x, y, z = p.T
    if len(set(z.tolist())) <= 1:
        v, axis, name = np.column_stack([x, y]), 2, "xy-plane as (x, y)"
    elif len(set(y.tolist())) == 1:
        v, axis, name = np.column_stack([x, 0.0 - z]), 1, "xz-plane as (x, -z), seen from +y"
    elif len(set(x.tolist())) == 1:
        v, axis, name = np.column_stack([y, z]), 0, "yz-plane as (y, z), seen from +x"
    else:  # a surface in space
        return p, ""
    if axis == 2 and (not len(p) or z[0] == 0):
        return v, ""
    return v, f"all vertices have {'xyz'[axis]} = {float(p[0, axis])!r}; read in the {name}"
