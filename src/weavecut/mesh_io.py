"""Read and write meshes: Wavefront OBJ and weave-cut's JSON.

JSON format (version 1)::

    {"format": "weave-cut-mesh", "version": 1,
     "vertices": [[x, y], ...],          # floats; [x, y, z] for a surface in space
     "faces": [[i, j, k, ...], ...]}     # 0-based vertex indices, counter-clockwise

Both round-trip exactly: floats are written with ``repr`` (shortest exact form).

Reading is bounded: only regular files (a FIFO, device or directory is refused before it is
read), at most ``MAX_BYTES`` of the format (1 GiB OBJ, 512 MiB JSON: reading takes 3 to 4, and
10 to 16, times the size in memory), ``MAX_FACES`` faces and ``MAX_VERTICES`` vertices; JSON
nesting and number sizes are bounded too. An OBJ is parsed with numpy, ``CHUNK`` bytes of whole
lines at a time (so the scratch arrays stay in the processor's cache); messages about it count
faces and vertices from 1 and give the line, as OBJ users count.
"""

from __future__ import annotations

import json
import os
import stat
import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import readers
from .errors import MeshError, MeshFileError
from .fileio import write_atomic
from .mesh import ZERO_BASED, Mesh, Numbering, check_structure

JSON_FORMAT = "weave-cut-mesh"
SUFFIXES = (".obj", ".json")
MAX_FACES = 2**24  # 16.8 million, 1.7 times the pentagon's level 10
MAX_VERTICES = 2**25
# Reading takes 3 to 4 (OBJ) and 10 to 16 (JSON) times the file's size in memory, so these keep
# it under about 5 GiB.
# weave-cut writes 46 (quads) to 96 (snub pentagons) bytes per face in OBJ, 44 in JSON,
# Blender ~130 with UVs and normals: 8 to 23 million faces, more than any level is useful.
MAX_BYTES = {".obj": 2**30, ".json": 2**29}

Note = Callable[[str], None]


def read_mesh(path: str | Path, note: Note | None = None, **drawing_options) -> Mesh:
    """Read an OBJ or JSON mesh, or an SVG or DXF drawing (``drawing_options``: see
    ``readers.read_drawing``); MeshFileError names the file and line of a problem.

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
    return json.dumps(doc, separators=(",", ":")) + "\n"


def _read(path: Path, note: Note | None, drawing_options: dict) -> tuple[Mesh, Numbering]:
    suffix = path.suffix.lower()
    if suffix in readers.SUFFIXES:
        return readers.read_drawing(path, report=note, **drawing_options), ZERO_BASED
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
            mesh, numbering, remark = _parse_obj(raw)
            if remark and note:
                note(f"{path}: {remark}")
            return mesh, numbering
        return _parse_json(text), ZERO_BASED
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


# -- OBJ ------------------------------------------------------------------------------------

_IGNORED = (b"vt", b"vn", b"vp", b"o", b"g", b"s", b"usemtl", b"mtllib", b"l")
_CONTROLS = np.array([c if c in (10, 13) or c > 31 else 32 if c in (9, 11, 12) else 127
                      for c in range(256)], dtype=np.uint8)  # see _normalise_controls
MAX_TOKEN = 40  # longer numbers are parsed one by one
CHUNK = 2**18  # bytes of whole lines parsed at once: their scratch arrays stay in the cache
_ZEROS = np.uint64(0x3030303030303030)  # "00000000"
_HIGH_NIBBLES = np.uint64(0xF0F0F0F0F0F0F0F0)
_LOW_BYTES = np.array([(1 << 8 * k) - 1 for k in range(9)], dtype=np.uint64)
MAX_DIGITS = 19  # a decimal of up to 19 digits is an exact uint64 (10**19 < 2**64)
_POWERS = np.array([10**k for k in range(MAX_DIGITS + 1)], dtype=np.uint64)
_POWERS_F8, _POWERS_LD = _POWERS.astype(np.float64), _POWERS.astype(np.longdouble)
# long double is the x87 80-bit number (64-bit significand first, little-endian) on x86
_X87 = np.finfo(np.longdouble).nmant == 63 and sys.byteorder == "little"


def _key(tag: bytes) -> np.uint64:
    return np.frombuffer(tag.ljust(8, b"\0"), dtype=np.uint64)[0]


class _Tokens:
    """The whitespace-separated tokens of an OBJ text, as byte offsets, grouped into lines.

    Comments and carriage returns are removed first, so line ``n`` is the n-th line of the
    text, counted on from ``lines_before``. Only non-empty lines are kept: ``line`` (1-based
    number), ``first`` (its first token, the statement) and ``count`` (tokens on it, the
    statement included); ``n_lines`` counts the text's line ends.
    """

    def __init__(self, data, lines_before: int = 0, comments: bool = True) -> None:
        pad = b" " * MAX_TOKEN  # room for windows of bytes before and after every token
        ends = data[-1:] == b"\n"
        self.buf = np.frombuffer(bytearray().join([pad, data, b"" if ends else b"\n", pad]),
                                 dtype=np.uint8)
        text = self.buf[:-MAX_TOKEN]
        gap = self._gaps(text)
        newline = text[gap] == 10
        n_newlines = int(np.count_nonzero(newline))
        if n_newlines + np.count_nonzero(text[gap] == 32) < len(gap):  # other control bytes
            _normalise_controls(text)
            gap = self._gaps(text)
            newline = text[gap] == 10
            n_newlines = int(np.count_nonzero(newline))
        self.n_lines = n_newlines - (not ends)
        if comments:
            _blank_comments(text, gap[newline])
            gap = self._gaps(text)
            newline = text[gap] == 10
        # a token lies between two gaps that are not next to each other
        self.start, self.end = gap[:-1] + 1, gap[1:]
        newline[0] = True  # the pad: the text starts a line
        if (self.end > self.start).all():  # no blank line, no run of spaces
            self.first = np.flatnonzero(newline[:-1])
            self.line = np.arange(1 + lines_before, 1 + lines_before + len(self.first))
        else:
            newline[0] = False
            line = np.cumsum(newline[:-1])  # of the space after each gap, 0-based
            token = np.flatnonzero(self.end > self.start)
            self.start, self.end, line = self.start[token], self.end[token], line[token]
            self.first = np.flatnonzero(np.diff(line, prepend=-1))
            self.line = line[self.first] + 1 + lines_before
        self.count = np.diff(self.first, append=len(self.start))

    @staticmethod
    def _gaps(text: np.ndarray) -> np.ndarray:
        """Positions of the bytes below 33 (spaces, line ends, control characters) from the
        pad byte just before the text on."""
        return np.flatnonzero(text[MAX_TOKEN - 1:] <= 32) + (MAX_TOKEN - 1)

    def text(self, token: int) -> str:
        """Token ``token`` as text (its first few hundred characters)."""
        a, b = int(self.start[token]), int(self.end[token])
        return self.buf[a:min(b, a + 800)].tobytes().decode("utf-8", errors="ignore")

    def keys(self, tokens) -> np.ndarray:
        """A uint64 key for each token of up to 8 bytes (0 for longer ones)."""
        length = self.end[tokens] - self.start[tokens]
        keys = self._items(8, "<u8")[self.start[tokens]]
        keys &= _LOW_BYTES[np.minimum(length, 8)]
        keys[length > 8] = 0
        return keys

    def _items(self, width: int, dtype) -> np.ndarray:
        """Item i is bytes i .. i + width - 1 of the text (overlapping, no copy)."""
        return np.ndarray(len(self.buf) - width + 1, dtype, self.buf, strides=(1,))

    def floats(self, tokens) -> tuple[np.ndarray, int | None]:
        """The tokens as float64 (Python's float syntax) and the position of the first one
        that is no number (or None): plain decimals here, the others by numpy."""
        start, end = self.start[tokens], self.end[tokens]
        values, plain = self._decimals(start, end)
        other = np.flatnonzero(~plain)
        if not len(other):
            return values, None
        values[other], bad = self._any_floats(start[other], end[other])
        return values, None if bad is None else int(other[bad])

    def _decimals(self, start, end) -> tuple[np.ndarray, np.ndarray]:
        """Correctly rounded values of the tokens that are plain decimals, ``[+-]digits[.digits]``
        with 1 to 19 digits, at most 7 before the point, and the mask of those converted (the
        other values are arbitrary).

        The digits make an integer m < 10**19 < 2**64 and the value is m / 10**k. Up to 2**53
        both are exact doubles and one division rounds correctly; above, the quotient is
        taken in x87 long double (64-bit significand) and rounded again to double, which is
        correct unless the long double lies halfway between two doubles (those few are
        left out, as is every m > 2**53 where long double is no x87 number).
        """
        first = self.buf[start]
        negative = first == ord("-")
        start = start + (negative | (first == ord("+")))
        head = self._items(8, "<u8")[start]  # the first 8 bytes, where the point must be
        length = end - start
        n_whole = np.minimum(_first_byte(head, ord(".")), length)  # 8: no point in the head
        n_part = np.maximum(length - n_whole - 1, 0)
        whole, plain = _swar_digits(_right_aligned(head, n_whole))
        part, part_ok = self._digits(end, np.minimum(n_part, MAX_DIGITS))
        plain &= part_ok & (n_whole < 8) & (0 < n_whole + n_part) & (n_whole + n_part <= MAX_DIGITS)
        n_part = np.minimum(n_part, MAX_DIGITS)
        m = whole * _POWERS[n_part] + part  # wraps around only for tokens left out
        values = m.astype(np.float64) / _POWERS_F8[n_part]
        big = np.flatnonzero(m > 2**53)
        if len(big) and _X87:
            wide = m[big].astype(np.longdouble) / _POWERS_LD[n_part[big]]
            values[big] = wide.astype(np.float64)
            significand = np.ndarray(len(wide), np.uint64, wide, strides=(wide.itemsize,))
            plain[big] &= (significand & np.uint64(0x7FF)) != 0x400  # not halfway
        else:
            plain[big] = False
        np.negative(values, out=values, where=negative)
        return values, plain

    def _any_floats(self, start, end) -> tuple[np.ndarray, int | None]:
        """The tokens as float64 by numpy's conversion (Python's syntax: exponents, ``nan``,
        ``1_0``) and the position of the first that is no number (or None)."""
        length = end - start
        width = int(min(length.max(initial=1), MAX_TOKEN))
        strings = self._items(width, f"S{width}")[start]
        window = strings.view(np.uint8).reshape(-1, width)
        window *= np.arange(width) < length[:, None]  # NUL after each number
        long = np.flatnonzero(length > width)
        window[long] = ord("0")  # decided one by one below
        try:
            values, bad = strings.astype(np.float64), []
        except ValueError:
            first_bad = _first_unconvertible(strings)
            values = np.full(len(strings), np.nan)
            values[:first_bad] = strings[:first_bad].astype(np.float64)
            bad = [first_bad]
        for i in long.tolist():
            try:
                values[i] = float(self.buf[start[i]:end[i]].tobytes())
            except ValueError:
                bad.append(i)
        return values, min(bad, default=None)

    def ints(self, start, end) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Whole numbers ``[+-]digits`` in the given bytes: (int64 values, not-a-number mask,
        mask of those with more than 16 digits, whose value is not computed)."""
        first = self.buf[start]
        sign = (end > start) & ((first == ord("+")) | (first == ord("-")))
        length = end - start - sign
        values, ok = self._digits(end, np.minimum(length, 16))
        values = values.astype(np.int64)
        bad = (length == 0) | ~ok
        long = np.flatnonzero(length > 16)
        if len(long):  # check the rest of their digits, eight at a time
            chunks = (length[long] - 9) // 8
            rest = np.repeat(length[long] - 16, chunks)
            step = 8 * (np.arange(len(rest)) - np.repeat(np.cumsum(chunks) - chunks, chunks))
            ok = self._eight_digits(np.repeat(end[long] - 16, chunks) - step,
                                    np.minimum(rest - step, 8))[1]
            bad[long] |= ~np.logical_and.reduceat(ok, np.cumsum(chunks) - chunks)
        too_long = np.zeros(len(start), dtype=bool)
        too_long[long] = ~bad[long]
        return np.where(sign & (first == ord("-")), -values, values), bad, too_long

    def _digits(self, end, length) -> tuple[np.ndarray, np.ndarray]:
        """The number (uint64) of the ``length`` (0..19) digits before each ``end``, and
        whether they are all digits."""
        value, ok = self._eight_digits(end, np.minimum(length, 8))
        for k in (8, 16):
            longer = np.flatnonzero(length > k)
            if not len(longer):
                break
            high, high_ok = self._eight_digits(end[longer] - k, np.minimum(length[longer] - k, 8))
            value[longer] += high * _POWERS[k]
            ok[longer] &= high_ok
        return value, ok

    def _eight_digits(self, end, length) -> tuple[np.ndarray, np.ndarray]:
        """The number of the ``length`` (0..8) digits before each ``end``, and whether they
        are all digits."""
        return _swar_digits(_right_aligned(self._items(8, "<u8")[end - 8], length, ends=True))


def _right_aligned(words, length, ends: bool = False) -> np.ndarray:
    """In place: the eight bytes of ``words`` with the ``length`` bytes of a number at their
    end (``ends``) or start moved to the end, the bytes before it "0"."""
    if not ends:
        words <<= (8 * (8 - length)).astype(np.uint64)  # shifts of 64 give 0
    pad = _LOW_BYTES[8 - length]
    words |= pad
    words ^= pad & ~_ZEROS
    return words


def _swar_digits(d) -> tuple[np.ndarray, np.ndarray]:
    """In place: the numbers that the eight ASCII digits in each uint64 spell (the first in
    the lowest byte), and whether they are all digits (SWAR: eight bytes at a time)."""
    ok = (d & _HIGH_NIBBLES) == _ZEROS
    ok &= ((d + np.uint64(0x0606060606060606)) & _HIGH_NIBBLES) == _ZEROS
    d &= np.uint64(0x0F0F0F0F0F0F0F0F)  # a digit 0..9 in each byte
    for shift, mask, scale in ((8, 0x00FF00FF00FF00FF, 2561), (16, 0x0000FFFF0000FFFF, 6553601),
                               (32, 0xFFFFFFFF, 42949672960001)):
        d *= np.uint64(scale)  # pairs of digits, then fours, then eight: 10 * a + b ...
        d >>= np.uint64(shift)
        d &= np.uint64(mask)
    return d, ok


def _first_byte(words, byte: int) -> np.ndarray:
    """Position (0..7) of the first ``byte`` in each uint64's eight bytes, 8 if none."""
    x = words ^ np.uint64(byte * 0x0101010101010101)
    found = ~(((x & np.uint64(0x7F7F7F7F7F7F7F7F)) + np.uint64(0x7F7F7F7F7F7F7F7F)) | x)
    found &= np.uint64(0x8080808080808080)  # the high bit of each byte that was ``byte``
    lowest = (found & (~found + np.uint64(1))) >> np.uint64(7)  # 1 << 8 * position, or 0
    lowest *= np.uint64(0x0807060504030201)  # its top byte: 8 - position
    return 8 - (lowest >> np.uint64(56)).astype(np.int64)


def _normalise_controls(text: np.ndarray) -> None:
    """In place: CR LF and a lone CR end a line like LF; tab, vertical tab and form feed are
    spaces; other control characters become DEL, which no number or statement contains."""
    cr = np.flatnonzero(text == 13)
    text[cr] = np.where(text[cr + 1] == 10, 32, 10)
    text[:] = _CONTROLS[text]


def _blank_comments(text: np.ndarray, line_end: np.ndarray) -> None:
    """In place: spaces from every ``#`` to the end of its line."""
    hashes = np.flatnonzero(text == ord("#"))
    end = line_end[np.searchsorted(line_end, hashes)]
    first = np.flatnonzero(np.diff(end, prepend=-1))  # the first # of each line
    start, length = hashes[first], end[first] - hashes[first]
    text[np.repeat(start - np.cumsum(length) + length, length) + np.arange(length.sum())] = 32


def _first_unconvertible(strings: np.ndarray) -> int:
    """Position of the first entry that does not convert to float (one is known to exist)."""
    lo, hi = 0, len(strings)
    while hi - lo > 1:  # bisect, converting halves in C
        mid = (lo + hi) // 2
        try:
            strings[lo:mid].astype(np.float64)
            lo = mid
        except ValueError:
            hi = mid
    return lo


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


def _parse_obj(data: bytes) -> tuple[Mesh, Numbering, str]:
    """Mesh, 1-based numbering with face lines, and a remark about the plane ("" if none).

    The text is parsed a piece at a time; a bad line raises at once (lines come in order), a
    face index that refers to no vertex once every line is known good.
    """
    parts, n_lines, n_vertices, n_faces = [], 0, 0, 0
    for chunk, comments in _line_chunks(data):
        tok = _Tokens(chunk, n_lines, comments)
        parts.append(_obj_part(tok, n_vertices))
        n_lines += tok.n_lines
        n_vertices += len(parts[-1].v_line)
        n_faces += len(parts[-1].f_line)
        if n_faces > MAX_FACES or n_vertices > MAX_VERTICES:
            raise MeshFileError(f"more than {MAX_FACES:,} faces or {MAX_VERTICES:,} vertices "
                                f"by line {n_lines:,}; weave-cut reads at most that")
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


def _obj_part(tok: _Tokens, n_vertices: int) -> _Part:
    """The statements of one piece, whose text follows ``n_vertices`` vertices; raises
    MeshFileError at its first bad line."""
    single = tok.end[tok.first] - tok.start[tok.first] == 1
    tag = tok.buf[tok.start[tok.first]]
    is_v, is_f = single & (tag == ord("v")), single & (tag == ord("f"))
    errors: list[tuple[int, int, str]] = []  # (line, rank on the line, message)
    other = np.flatnonzero(~(is_v | is_f))
    if len(other):
        other = other[~np.isin(tok.keys(tok.first[other]), [_key(t) for t in _IGNORED])]
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


def _obj_vertices(tok: _Tokens, first, n_numbers, lines, errors) -> np.ndarray:
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


def _obj_faces(tok: _Tokens, first, sizes, lines, errors) -> np.ndarray:
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


def _plain_indices(tok: _Tokens, first, sizes) -> np.ndarray | None:
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


# -- JSON -----------------------------------------------------------------------------------

def _parse_json(text: str) -> Mesh:
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
    if len(faces) > MAX_FACES or len(vertices) > MAX_VERTICES:
        raise MeshFileError(f"{len(faces):,} faces and {len(vertices):,} vertices; weave-cut "
                            f"reads at most {MAX_FACES:,} faces and {MAX_VERTICES:,} vertices")
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
