"""weave-cut's JSON mesh format (version 1)::

    {"format": "weave-cut-mesh", "version": 1,
     "vertices": [[x, y], ...],          # floats; [x, y, z] for a surface in space
     "faces": [[i, j, k, ...], ...]}     # 0-based vertex indices, counter-clockwise

read with bounded nesting, number sizes and counts (``readers.MAX_FACES``, ``MAX_VERTICES``)."""

from __future__ import annotations

import json

import numpy as np

from .. import readers
from ..errors import MeshFileError
from ..mesh import Mesh

JSON_FORMAT = "weave-cut-mesh"


def parse_json(text: str) -> Mesh:
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise MeshFileError(f"invalid JSON at line {exc.lineno}: {exc.msg}") from None
    except RecursionError:
        raise MeshFileError("JSON nested too deeply (a mesh needs 3 levels)") from None
    except ValueError:  # an integer of more digits than Python converts (4300)
        raise MeshFileError("a number in the JSON is too large (thousands of digits)") from None
    if not isinstance(doc, dict) or doc.get("format") != JSON_FORMAT:
        raise MeshFileError(f"not a weave-cut mesh (expected \"format\": \"{JSON_FORMAT}\")")
    if doc.get("version") != 1:
        raise MeshFileError(f"unsupported version {doc.get('version')!r}; this reads version 1")
    vertices, faces = doc.get("vertices"), doc.get("faces")
    if not isinstance(vertices, list) or not isinstance(faces, list):
        raise MeshFileError("\"vertices\" and \"faces\" must be lists")
    if len(faces) > readers.MAX_FACES or len(vertices) > readers.MAX_VERTICES:
        raise MeshFileError(f"{len(faces):,} faces and {len(vertices):,} vertices; weave-cut "
                            f"reads at most {readers.MAX_FACES:,} faces and "
                            f"{readers.MAX_VERTICES:,} vertices")
    dim = len(vertices[0]) if vertices and isinstance(vertices[0], list) else 2
    for i, v in enumerate(vertices):
        if (not isinstance(v, list) or len(v) != dim or dim not in (2, 3)
                or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in v)):
            like = f"{'[x, y, z]' if dim == 3 else '[x, y]'} numbers like vertex 0"
            want = "[x, y] or [x, y, z]" if i == 0 else like
            raise MeshFileError(f"vertex {i} must be {want}, got {v!r}"[:120])
    for i, f in enumerate(faces):
        if not isinstance(f, list) or not all(type(j) is int for j in f):
            raise MeshFileError(f"face {i} must be a list of vertex indices, got {f!r}"[:120])
    if not faces:
        raise MeshFileError("the mesh has no faces")
    try:
        points = np.array(vertices, dtype=float).reshape(-1, dim)
    except OverflowError:
        raise MeshFileError("a vertex coordinate is too large for a float") from None
    return Mesh.from_faces(points, faces)
