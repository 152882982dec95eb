"""Drawings and meshes people upload: size-bounded, the format sniffed from the bytes (the
first 4 KiB, in the server), read with the same bounded readers the CLI uses
(``mesh_io.read_valid_mesh``) in a job process with the CPU and memory limits of a kit (a
"read" job, ``read_job``: a reader that crashes or runs out of memory ends that process, not
the server), and kept under their SHA-256 in the app's folder only once they read, never
under a name from the request.

``input=upload:ID`` names one in a query; a job gets its bytes under the bare name
``upload-ID.svg`` (``.dxf``, ``.obj``, ``.json``) in its own folder.
"""

from __future__ import annotations

import hashlib
import re
import tempfile
from pathlib import Path

from ..errors import WeaveCutError
from ..fileio import write_atomic
from .jobs import JobResult, JobSpec, failed

MAX_BYTES = 8 * 2**20  # a hand-made drawing is kilobytes; an OBJ of 100,000 faces about 5 MiB
FORMATS = (".svg", ".dxf", ".obj", ".json")
READ = "read"  # the kind of job that reads an upload
KINDS = ("surface", "flat")  # the kinds of kit an upload makes (``strands_command.kit_kind``)
_OBJ_LINE = re.compile(rb"\s*(v|vt|vn|f|l|o|g|s|usemtl|mtllib)\s")


class UploadError(ValueError):
    """An upload refused: ``status`` 400 (unreadable), 413 (too large) or 404 (unknown id)."""

    def __init__(self, message: str, status: int = 400) -> None:
        super().__init__(message)
        self.message, self.status = message, status


def sniff(data: bytes) -> str:
    """The suffix of the format ``data`` is in, by its bytes (never by a name or header)."""
    head = data[:4096].lstrip(b"\xef\xbb\xbf \t\r\n")
    if head.startswith(b"AutoCAD Binary DXF"):
        return ".dxf"
    if head.startswith(b"<") and b"<svg" in head:
        return ".svg"
    if head.startswith(b"{"):
        return ".json"
    lines = [w.strip() for w in head.splitlines()[:12]]
    if any(a == b"0" and b == b"SECTION" for a, b in zip(lines, lines[1:])):
        return ".dxf"
    if any(_OBJ_LINE.match(line) for line in head.splitlines() if not line.startswith(b"#")):
        return ".obj"
    raise UploadError("not a drawing or mesh weave-cut reads: upload an SVG or DXF drawing, "
                      "or an OBJ or weave-cut JSON mesh")


def check(data: bytes, suffix: str) -> str:
    """Read ``data`` as the CLI reads a file of ``suffix`` (its bounded readers and the mesh
    checks): the kind of kit it makes as ``strands`` sees it ("surface": a ball, "flat";
    ``kit_kind``); UploadError with the reader's message, the temporary path said as 'the
    file'."""
    from ..cli.strands_command import kit_kind
    from ..mesh_io import read_valid_mesh

    with tempfile.TemporaryDirectory(prefix="weavecut-upload-") as tmp:
        path = Path(tmp) / f"upload{suffix}"
        path.write_bytes(data)
        try:
            return kit_kind(read_valid_mesh(path, allow_nonconvex=True))
        except WeaveCutError as exc:
            raise UploadError(str(exc).replace(str(path), f"the {suffix[1:].upper()} file")
                              .replace(tmp, "")) from None
        except (ValueError, KeyError, IndexError, TypeError, OSError, RecursionError) as exc:
            # a reader's own parser giving up on malformed bytes
            raise UploadError(f"the {suffix[1:].upper()} file cannot be read "
                              f"({type(exc).__name__})") from None


def read_job(spec: JobSpec) -> JobResult:
    """Read the one file of a "read" job as ``check`` does (in the job's process, under its
    limits): ok with the format and the kind of kit in its summary, or the reader's message
    (400; 413 when the reader ran out of the memory a job may use)."""
    if len(spec.files) != 1 or Path(spec.files[0][0]).suffix not in FORMATS:
        return failed(400, "a read job reads one .svg, .dxf, .obj or .json file")
    name, data = spec.files[0]
    suffix = Path(name).suffix
    try:
        kind = check(data, suffix)
    except UploadError as exc:
        return failed(exc.status, exc.message)
    except MemoryError:
        return failed(413, f"the {suffix[1:].upper()} file needs more memory to read than an "
                      "upload may use; simplify the drawing or mesh")
    return JobResult(True, b"", "text/plain; charset=utf-8", {"format": suffix[1:],
                                                              "kind": kind})


def read_spec(data: bytes, suffix: str) -> JobSpec:
    """The job that reads ``data`` as a file of ``suffix``."""
    return JobSpec(READ, "upload", (), ((f"upload{suffix}", data),))


class Store:
    """Uploads kept in ``folder``, each as ``SHA256.SUFFIX``, with the kind of kit it makes
    (``check``) in ``SHA256.kind``."""

    def __init__(self, folder: Path) -> None:
        self.folder = Path(folder)

    def screen(self, data: bytes) -> tuple[str, str]:
        """(id, suffix) of ``data``: its SHA-256 hex and its format by its first bytes;
        UploadError if it is empty, too large or no format weave-cut reads. The bytes are not
        read as a drawing here: a "read" job does (``read_spec``), then ``keep``."""
        if len(data) > MAX_BYTES:
            raise UploadError(f"{len(data):,} bytes; an upload is at most "
                              f"{MAX_BYTES >> 20} MiB", 413)
        if not data:
            raise UploadError("the upload is empty")
        return hashlib.sha256(data).hexdigest(), sniff(data)

    def keep(self, data: bytes, kind: str = "") -> str:
        """Keep ``data``, which a read job has read as a ``kind`` of kit; its id."""
        ident, suffix = self.screen(data)
        if self.find(ident) is None:
            self.folder.mkdir(parents=True, exist_ok=True)
            if kind in KINDS:  # first: an upload kept is never without its kind
                write_atomic(self.folder / f"{ident}.kind", kind.encode())
            write_atomic(self.folder / f"{ident}{suffix}", data)
        return ident

    def kind(self, ident: str) -> str:
        """The kind of kit upload ``ident`` makes ("surface", "flat"); "" if unknown."""
        path = self.folder / f"{ident}.kind"
        if not re.fullmatch(r"[0-9a-f]{64}", ident) or not path.is_file():
            return ""
        kind = path.read_text(encoding="ascii", errors="replace")
        return kind if kind in KINDS else ""

    def find(self, ident: str) -> Path | None:
        if not re.fullmatch(r"[0-9a-f]{64}", ident):
            return None
        found = [self.folder / f"{ident}{s}" for s in FORMATS
                 if (self.folder / f"{ident}{s}").is_file()]
        return found[0] if found else None

    def argument(self, ident: str) -> tuple[str, Path]:
        """The INPUT word of upload ``ident`` (the bare name a job writes it under) and the
        file it is kept in."""
        path = self.find(ident)
        if path is None:
            raise UploadError(f"no upload {ident[:12]}; upload the drawing again")
        return f"upload-{ident}{path.suffix}", path
