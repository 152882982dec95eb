"""glTF 2.0 binary (``.glb``) of a :class:`weavecut.weave.woven.Model`, written by hand: the
same model gives the same bytes (no generator time stamp, parts and materials in a fixed
order), and nothing beyond numpy is needed.

z up becomes glTF's y up. One mesh, one primitive per part (a strand, a piece's front, back or edge) with its own
vertices (POSITION and NORMAL, float32, in metres) and indices (uint32); one material per
colour, its sRGB colour turned into glTF's linear ``baseColorFactor``, rough, not metallic, and
double-sided (paper is seen from both sides).
"""

from __future__ import annotations

import json
import struct

import numpy as np

from ..errors import ExportError
from ..numeric import distinct

GLB_MAGIC, JSON_CHUNK, BIN_CHUNK = 0x46546C67, 0x4E4F534A, 0x004E4942
FLOAT, UINT = 5126, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
MAX_BYTES = 64 * 2**20  # a kit's model stays well below; a larger one is refused


def linear(colour: str) -> list[float]:
    """glTF's linear RGBA of an sRGB ``#rrggbb``, rounded to 6 digits.

    >>> linear("#ffffff"), linear("#000000")
    ([1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0])
    """
    c = np.array([int(colour[i:i + 2], 16) for i in (1, 3, 5)]) / 255.0
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return [round(float(x), 6) for x in lin] + [1.0]


def y_up(points: np.ndarray) -> np.ndarray:
    """weave-cut's z-up (x, y, z) as glTF's y-up (x, z, -y): a flat model lies on the floor."""
    return np.column_stack([points[:, 0], points[:, 2], -points[:, 1]])


def glb_bytes(model, metres_per_unit: float = 0.001, name: str = "weave-cut model") -> bytes:
    """The model as glTF binary, its lengths times ``metres_per_unit`` (mm -> m by default)."""
    order = np.argsort(model.part, kind="stable")  # the parts' triangles, part after part
    part, triangles = model.part[order], model.triangles[order]
    parts = distinct(part)  # in order (without np.unique's numpy.ma import)
    colours = sorted(set(model.colours[p] for p in parts.tolist()))
    material_of = {c: k for k, c in enumerate(colours)}
    # each part's own vertices, ascending, and its triangles' indices into them, all at once
    rank = np.searchsorted(parts, part)
    n = len(model.vertices)
    used, local = np.unique((rank[:, None] * n + triangles).ravel(), return_inverse=True)
    first = np.searchsorted(used // n, np.arange(len(parts) + 1))  # each part's first vertex
    cuts = np.searchsorted(rank, np.arange(len(parts) + 1)) * 3  # ... and first index
    positions = (y_up(model.vertices[used % n]) * metres_per_unit).astype("<f4")
    normals = y_up(model.normals[used % n]).astype("<f4")
    low = np.minimum.reduceat(positions, first[:-1]).tolist() if len(parts) else []
    high = np.maximum.reduceat(positions, first[:-1]).tolist() if len(parts) else []
    local = (local.reshape(-1) - np.repeat(first[:-1], np.diff(cuts))).astype("<u4")
    chunks: list[bytes] = []
    views, accessors, primitives = [], [], []
    offset = 0

    def add(data: np.ndarray, target: int, component: int, kind: str, bounds=None) -> int:
        nonlocal offset
        raw = data.tobytes()
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(raw),
                      "target": target})
        chunks.append(raw + b"\0" * (-len(raw) % 4))
        offset += len(raw) + (-len(raw) % 4)
        accessor = {"bufferView": len(views) - 1, "componentType": component,
                    "count": len(data) if kind != "SCALAR" else data.size, "type": kind}
        if bounds is not None:
            accessor["min"], accessor["max"] = bounds
        accessors.append(accessor)
        return len(accessors) - 1

    for i, p in enumerate(parts.tolist()):
        mine = slice(first[i], first[i + 1])
        position = add(positions[mine], ARRAY_BUFFER, FLOAT, "VEC3", (low[i], high[i]))
        normal = add(normals[mine], ARRAY_BUFFER, FLOAT, "VEC3")
        index = add(local[cuts[i]:cuts[i + 1]], ELEMENT_ARRAY_BUFFER, UINT, "SCALAR")
        primitives.append({"attributes": {"POSITION": position, "NORMAL": normal},
                           "indices": index, "material": material_of[model.colours[p]],
                           "extras": {"name": model.names[p]}})
    document = {
        "asset": {"version": "2.0", "generator": "weave-cut"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": name}],
        "meshes": [{"name": name, "primitives": primitives}],
        "materials": [{"name": c, "doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": linear(c), "metallicFactor": 0.0, "roughnessFactor": 0.85}}
            for c in colours],
        "accessors": accessors, "bufferViews": views, "buffers": [{"byteLength": offset}],
    }
    text = json.dumps(document, separators=(",", ":"), allow_nan=False).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary = b"".join(chunks)
    total = 12 + 8 + len(text) + 8 + len(binary)
    if total > MAX_BYTES:
        raise ExportError(f"the 3-D model would be {total / 2**20:.0f} MiB; the limit is "
                          f"{MAX_BYTES // 2**20} MiB")
    return b"".join([struct.pack("<III", GLB_MAGIC, 2, total),
                     struct.pack("<II", len(text), JSON_CHUNK), text,
                     struct.pack("<II", len(binary), BIN_CHUNK), binary])
