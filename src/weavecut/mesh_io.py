"""Read and write meshes: Wavefront OBJ and weave-cut's JSON (``readers.mesh_json``), and
read drawings (SVG, DXF) as meshes; the formats are read in ``readers/``.

OBJ and JSON round-trip exactly: floats are written with ``repr`` (shortest exact form).

Reading is bounded: only regular files (a FIFO, device or directory is refused before it is
read), at most ``MAX_BYTES`` of the format (1 GiB OBJ, 512 MiB JSON: reading takes 3 to 4, and
10 to 16, times the size in memory), ``readers.MAX_FACES`` faces and ``readers.MAX_VERTICES``
vertices; JSON nesting and number sizes are bounded too.
"""

from __future__ import annotations

import json
import os
import stat
from collections.abc import Callable
from pathlib import Path

from . import readers
from .errors import MeshError, MeshFileError
from .fileio import write_atomic
from .mesh import ZERO_BASED, Mesh, Numbering
from .readers.mesh_json import JSON_FORMAT, parse_json
from .readers.obj import parse_obj

SUFFIXES = (".obj", ".json")
# Reading takes 3 to 4 (OBJ) and 10 to 16 (JSON) times the file's size in memory, so these keep
# it under about 5 GiB.
# weave-cut writes 46 (quads) to 96 (snub pentagons) bytes per face in OBJ, 44 in JSON,
# Blender ~130 with UVs and normals: 8 to 23 million faces, more than any level is useful.
MAX_BYTES = {".obj": 2**30, ".json": 2**29}

Note = Callable[[str], None]


def read_mesh(path: str | Path, note: Note | None = None, **drawing_options) -> Mesh:
    """Read an OBJ or JSON mesh, or an SVG or DXF drawing (``drawing_options``: see
    ``readers.drawing.read_drawing``); MeshFileError names the file and line of a problem.

    ``note`` receives remarks that are no errors (an OBJ read in the xz- or yz-plane, what a
    drawing held).
    """
    return _read(Path(path), note, drawing_options)[0]


def read_valid_mesh(path: str | Path, *, allow_nonconvex: bool = False,
                    note: Note | None = None, **drawing_options) -> Mesh:
    """Read a mesh file and validate it; errors name the file and count as the file does
    (faces and vertices from 1, with line numbers, in an OBJ)."""
    from .validation import validate  # shapely and scipy: only where a file is validated

    path = Path(path)
    mesh, numbering = _read(path, note, {**drawing_options, "allow_nonconvex": allow_nonconvex})
    try:
        return validate(mesh, allow_nonconvex=allow_nonconvex, numbering=numbering)
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
    lines += [f"v {x!r} {y!r} {z[0]!r}" if z else f"v {x!r} {y!r} 0"
              for x, y, *z in mesh.vertices.tolist()]
    lines += ["f " + " ".join(str(i + 1) for i in face) for face in mesh.faces()]
    return "\n".join(lines) + "\n"


def json_text(mesh: Mesh, metadata: dict[str, str] | None = None) -> str:
    doc = {"format": JSON_FORMAT, "version": 1, **(metadata or {}),
           "vertices": mesh.vertices.tolist(), "faces": mesh.faces()}
    return json.dumps(doc, separators=(",", ":"), allow_nan=False) + "\n"


def _read(path: Path, note: Note | None, drawing_options: dict) -> tuple[Mesh, Numbering]:
    suffix = path.suffix.lower()
    if suffix in readers.SUFFIXES:
        from .readers.drawing import read_drawing  # shapely, svgelements: only for a drawing

        return read_drawing(path, report=note, **drawing_options), ZERO_BASED
    if suffix not in SUFFIXES:
        raise MeshFileError(f"{path}: unknown mesh format {path.suffix!r}; use .obj or .json, "
                            "or a drawing (.svg, .dxf)")
    raw = _read_regular_file(path, MAX_BYTES[suffix])
    try:
        text = "" if suffix == ".obj" and raw.isascii() else raw.decode("utf-8")
    except UnicodeDecodeError:
        raise MeshFileError(f"{path}: not a text file (not UTF-8)") from None
    try:
        if suffix == ".obj":  # parsed as bytes; the decoding only checks the encoding
            mesh, numbering, remark = parse_obj(raw)
            if remark and note:
                note(f"{path}: {remark}")
            return mesh, numbering
        return parse_json(text), ZERO_BASED
    except MeshError as exc:
        raise type(exc)(f"{path}: {exc}") from None


_KINDS = {stat.S_IFDIR: "a directory", stat.S_IFIFO: "a FIFO (named pipe)",
          stat.S_IFCHR: "a character device", stat.S_IFBLK: "a block device",
          stat.S_IFSOCK: "a socket"}


def _read_regular_file(path: Path, limit: int) -> bytes:
    """The bytes of ``path`` if it is a regular file of at most ``limit`` bytes.

    The file is opened non-blocking (a FIFO without a writer must not hang) and checked with
    fstat before a byte is read, so devices behind a symlink are refused too.
    """
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError as exc:
        raise MeshFileError(f"cannot read {path}: {exc.strerror}") from exc
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            kind = _KINDS.get(stat.S_IFMT(info.st_mode), "not a regular file")
            raise MeshFileError(f"{path}: is {kind}; mesh files must be regular files")
        if info.st_size > limit:
            raise MeshFileError(f"{path}: {info.st_size:,} bytes is more than the "
                                f"{limit >> 20:,} MiB weave-cut reads from a {path.suffix.lower()}"
                                " file")
        with os.fdopen(os.dup(fd), "rb") as f:
            data = f.read(info.st_size + 1)  # one byte more tells whether it grew
    except OSError as exc:
        raise MeshFileError(f"cannot read {path}: {exc.strerror}") from exc
    finally:
        os.close(fd)
    if len(data) > info.st_size:
        raise MeshFileError(f"{path}: the file grew while it was read")
    return data
