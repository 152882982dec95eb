"""Read and write meshes: Wavefront OBJ in the xy-plane and weave-cut's JSON.

JSON format (version 1)::

    {"format": "weave-cut-mesh", "version": 1,
     "vertices": [[x, y], ...],          # floats
     "faces": [[i, j, k, ...], ...]}     # 0-based vertex indices, counter-clockwise

Both round-trip exactly: floats are written with ``repr`` (shortest exact form).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from . import readers
from .errors import MeshError, MeshFileError
from .fileio import write_atomic
from .mesh import Mesh

JSON_FORMAT = "weave-cut-mesh"
SUFFIXES = (".obj", ".json")


def read_mesh(path: str | Path, **drawing_options) -> Mesh:
    """Read an OBJ or JSON mesh, or an SVG or DXF drawing (``readers.read_drawing`` and its
    options); MeshFileError names the file and line of a problem."""
    path = Path(path)
    if path.suffix.lower() in readers.SUFFIXES:
        return readers.read_drawing(path, **drawing_options)
    if path.suffix.lower() not in SUFFIXES:
        raise MeshFileError(f"{path}: unknown mesh format {path.suffix!r}; use .obj or .json")
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise MeshFileError(f"cannot read {path}: {exc.strerror}") from exc
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise MeshFileError(f"{path}: not a text file (not UTF-8)") from None
    parse = _parse_obj if path.suffix.lower() == ".obj" else _parse_json
    try:
        return parse(text)
    except MeshError as exc:
        raise type(exc)(f"{path}: {exc}") from None


def write_mesh(mesh: Mesh, path: str | Path, metadata: dict[str, str] | None = None) -> None:
    """Write ``mesh`` as OBJ or JSON (by suffix), atomically; ``metadata`` (generator,
    command) goes into OBJ comments or JSON keys that readers ignore."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".obj":
        data = obj_text(mesh, metadata)
    elif suffix == ".json":
        data = json_text(mesh, metadata)
    else:
        raise MeshFileError(f"{path}: unknown mesh format {path.suffix!r}; use .obj or .json")
    write_atomic(path, data.encode("utf-8"))


def obj_text(mesh: Mesh, metadata: dict[str, str] | None = None) -> str:
    lines = ["# weave-cut mesh", f"# {mesh.n_vertices} vertices, {mesh.n_faces} faces"]
    lines += [f"# {k}: {v}".replace("\n", " ") for k, v in (metadata or {}).items()]
    lines += [f"v {x!r} {y!r} 0" for x, y in mesh.vertices.tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in mesh.faces()]
    return "\n".join(lines) + "\n"


def json_text(mesh: Mesh, metadata: dict[str, str] | None = None) -> str:
    doc = {"format": JSON_FORMAT, "version": 1, **(metadata or {}),
           "vertices": mesh.vertices.tolist(), "faces": mesh.faces()}
    return json.dumps(doc, separators=(",", ":")) + "\n"


def _parse_obj(text: str) -> Mesh:
    vertices: list[tuple[float, float]] = []
    faces: list[list[int]] = []
    face_lines: list[int] = []
    face_seen: list[int] = []  # vertices defined before each face (for negative indices)
    for n, line in enumerate(text.splitlines(), start=1):
        parts = line.split("#", 1)[0].split() if "#" in line else line.split()
        if not parts:
            continue
        tag = parts[0]
        if tag == "v":
            vertices.append(_obj_vertex(parts[1:], n))
        elif tag == "f":
            try:
                faces.append([int(p.split("/", 1)[0]) for p in parts[1:]])
            except ValueError:
                raise MeshFileError(f"line {n}: face indices must be whole numbers") from None
            face_lines.append(n)
            face_seen.append(len(vertices))
        elif tag in ("vt", "vn", "vp", "o", "g", "s", "usemtl", "mtllib", "l"):
            continue
        else:
            raise MeshFileError(f"line {n}: unknown OBJ statement {tag!r}"[:200])
    if not faces:
        raise MeshFileError("no faces ('f' lines) found")
    sizes = np.fromiter(map(len, faces), dtype=np.int64, count=len(faces))
    try:
        flat = np.fromiter((i for f in faces for i in f), dtype=np.int64, count=int(sizes.sum()))
    except OverflowError:
        raise MeshFileError("a face index is too large") from None
    seen = np.repeat(np.array(face_seen, dtype=np.int64), sizes)
    bad = (flat == 0) | (np.abs(flat) > seen)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        f = int(np.searchsorted(np.cumsum(sizes), k, side="right"))
        raise MeshFileError(f"line {face_lines[f]}: face index {flat[k]} refers to no vertex "
                            f"({seen[k]} defined so far)")
    flat = np.where(flat > 0, flat - 1, seen + flat)
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    return Mesh(np.array(vertices, dtype=float).reshape(-1, 2), offsets, flat)


def _obj_vertex(fields: list[str], n: int) -> tuple[float, float]:
    if len(fields) < 2 or len(fields) > 4:
        raise MeshFileError(f"line {n}: a vertex needs x y [z], got {len(fields)} numbers")
    try:
        x, y, *rest = (float(f) for f in fields[:3])
    except ValueError:
        raise MeshFileError(f"line {n}: vertex coordinates must be numbers") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise MeshFileError(f"line {n}: vertex coordinate is not finite")
    if rest and rest[0] != 0.0:
        raise MeshFileError(f"line {n}: vertex has z = {rest[0]!r}; weave-cut meshes are planar "
                            "(z must be 0)")
    return (x, y)


def _parse_json(text: str) -> Mesh:
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise MeshFileError(f"invalid JSON at line {exc.lineno}: {exc.msg}") from None
    if not isinstance(doc, dict) or doc.get("format") != JSON_FORMAT:
        raise MeshFileError(f"not a weave-cut mesh (expected \"format\": \"{JSON_FORMAT}\")")
    if doc.get("version") != 1:
        raise MeshFileError(f"unsupported version {doc.get('version')!r}; this reads version 1")
    vertices, faces = doc.get("vertices"), doc.get("faces")
    if not isinstance(vertices, list) or not isinstance(faces, list):
        raise MeshFileError("\"vertices\" and \"faces\" must be lists")
    for i, v in enumerate(vertices):
        if (not isinstance(v, list) or len(v) != 2
                or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in v)):
            raise MeshFileError(f"vertex {i} must be [x, y] numbers, got {v!r}"[:120])
    for i, f in enumerate(faces):
        if not isinstance(f, list) or not all(type(j) is int for j in f):
            raise MeshFileError(f"face {i} must be a list of vertex indices, got {f!r}"[:120])
    if not faces:
        raise MeshFileError("the mesh has no faces")
    return Mesh.from_faces(np.array(vertices, dtype=float).reshape(-1, 2), faces)
